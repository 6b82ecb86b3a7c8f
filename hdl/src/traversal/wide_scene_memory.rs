//! The traversal unit's scene memory for wide nodes: a version-3 image (docs/scene-image.md
//! "Wide nodes") in two block RAMs, one wide node and one triangle per word, filled by a
//! checking loader from an AXI4-Stream of 32-bit words. The binary memory
//! ([`super::scene_memory`]) is its sibling: the same stream protocol, status outputs, header
//! and triangle checks and triangle read ports; the node records and their checks differ.
//!
//! Records: [`super::scene_records`] (`wide_node_record_bits`): a node's words 0 to 3 + 1.5·K
//! as they arrive (origin, exponents, child count, codes), then its K links of `LF` + 4 bits.
//!
//! The loader checks as the words pass: magic and version 3, N and T against the capacity,
//! the width K (word 13) equal to the memory's, the root node 0 (words 4 and 5 zero; with N = 0
//! only for an empty scene), S as version 2's, reserved header words 14–15, every node's child
//! count 1..K, its unused code bytes and link words 0, every used link in range (an inner node
//! below N, a leaf within T; a leaf's count field has 4 bits, so it holds at most 15), the
//! triangles as version 2's, and `tlast` on the image's last word. What needs the whole tree
//! (a node reached twice, a child's box enclosing its triangles, inverted codes, duplicate
//! global indices) is the driver's: it runs `WideImage::from_words` before streaming.
//!
//! Read ports: an address in, the record's fields out one cycle later (block RAM read latency):
//! the node's fields as [`super::wide::WideBoxStage`] takes them, its links as `first` (`LF`
//! bits) with `count` above.
//!
//! rust-hdl cannot derive widths: `NB`, `TB` address bits, `LF` a link's first, `LK` a link,
//! `HB` a record's head (origin to codes), `LB` its links, `NW`, `TW` the records, all checked
//! by [`WideSceneMemory::new`]; the aliases below fix them per configuration.

use rust_hdl::prelude::*;

use super::scene_memory::{code, scene_memory_block, scene_memory_new, LoadState, STATE_BITS};
use super::scene_records::*;
use super::wide::{Code, Count};
use crate::defaults;
use hw_model::traversal::scene_image::{HEADER_WORDS, MAGIC, TRIANGLE_WORDS, VERSION_WIDE};
use hw_model::traversal::wide::image::node_words;
use hw_model::traversal::wide::WIDTHS;

/// Bits of the image's words per node ([`node_words`], at most 24), so of `last`'s
/// shift-and-add multiply.
const NODE_WORDS_BITS: usize = 5;

scene_memory_block! {
    #[hdl_gen]
    self,
    WideSceneMemory<NB, TB, LF, LK, HB, LB, NW, TW>,
    record_word_bits: 5,
    node_ports: {
        /// Node read port: the node at `node_address`, one cycle later.
        pub node_address: Signal<In, Bits<NB>>,
        pub origin: [Signal<Out, Bits<32>>; 3],
        pub exp: [Signal<Out, Bits<8>>; 3],
        pub children: Signal<Out, Count>,
        /// `lo[3·slot + axis]`, `hi[3·slot + axis]`: the stage's code ports.
        pub lo: Vec<Signal<Out, Code>>,
        pub hi: Vec<Signal<Out, Code>>,
        /// Per slot: `first` in the low `LF` bits, the leaf's count above (0: an inner node).
        pub link: Vec<Signal<Out, Bits<LK>>>,
    },
    node_registers: {
        /// The node being assembled: its head words shift in from the top, then its links.
        head: DFF<Bits<HB>>,
        links: DFF<Bits<LB>>,
        /// The node's child count, 6 × it (its code bytes), the first byte of this code word,
        /// the slot of this link word.
        node_children: DFF<Bits<8>>,
        code_bytes: DFF<Bits<8>>,
        code_byte: DFF<Bits<8>>,
        slot: DFF<Bits<8>>,
    },
    format_constants: {
        /// K, as header word 13 and a child count compare with it.
        width: Constant<Bits<32>>,
        max_children: Constant<Bits<8>>,
    },
    node_constants: {
        /// All ones where bit `s` of the words per node is set: `last` adds `N << s` masked.
        node_words_mask: Vec<Constant<Bits<32>>>,
        node_words_shift: Vec<Constant<Bits<8>>>,
        /// A code word's byte `i` (`byte_offset[i]` = i).
        byte_offset: Vec<Constant<Bits<8>>>,
        /// Shifts: a head word to the head's top, a link to the links' top, a leaf's count
        /// within a link, the links within the record; per slot its link in the record.
        head_top: Constant<Bits<16>>,
        links_top: Constant<Bits<16>>,
        link_size: Constant<Bits<16>>,
        /// A link word's `first` bits.
        first_mask: Constant<Bits<32>>,
        at_count: Constant<Bits<16>>,
        at_links: Constant<Bits<16>>,
        link_at: Vec<Constant<Bits<16>>>,
    },
    record_ends: {
        head_end: Constant<Bits<5>>,
        node_end: Constant<Bits<5>>,
    },
    format_errors: {
        e_width: Constant<Bits<ERROR_CODE_BITS>>,
        e_child_count: Constant<Bits<ERROR_CODE_BITS>>,
    },
    word_signals: {},
    node_signals: {
        /// The image's last word from N and T (header word 3).
        image_end: Signal<Local, Bits<32>>,
        /// This word as a link: its first, its count, first + count (33 bits: no wrap), the
        /// link's record bits, the links with it shifted in.
        link_first: Signal<Local, Bits<32>>,
        link_count: Signal<Local, Bits<32>>,
        leaf_end: Signal<Local, Bits<33>>,
        link_bits: Signal<Local, Bits<LK>>,
        links_next: Signal<Local, Bits<LB>>,
        /// Where each byte of this code word is among the node's code bytes.
        byte_at: Vec<Signal<Local, Bits<8>>>,
        /// This word's byte 3 (a child count).
        count_byte: Signal<Local, Bits<8>>,
    },
    read_signals: {
        /// The read record shifted to each slot's link.
        link_read: Vec<Signal<Local, Bits<NW>>>,
    },
    node_dffs: {
        head,
        links,
        node_children,
        code_bytes,
        code_byte,
        slot,
    },
    each_word: {
        // 16 + words·N + 12·T words with T this word: the last is one less.
        self.image_end.next =
            self.header_end.val() + (self.s_tdata.val() << 3) + (self.s_tdata.val() << 2);
        for s in 0..NODE_WORDS_BITS {
            self.image_end.next = self.image_end.val()
                + ((self.n.q.val() << self.node_words_shift[s].val())
                    & self.node_words_mask[s].val());
        }
        self.link_first.next = self.s_tdata.val() & self.first_mask.val();
        self.link_count.next = self.s_tdata.val() >> 28;
        self.leaf_end.next =
            bit_cast::<33, 32>(self.link_first.val()) + bit_cast::<33, 32>(self.link_count.val());
        self.link_bits.next = bit_cast::<LK, LF>(bit_cast::<LF, 32>(self.link_first.val()))
            | (bit_cast::<LK, 32>(self.link_count.val()) << self.at_count.val());
        self.links_next.next = (self.links.q.val() >> self.link_size.val())
            | (bit_cast::<LB, LK>(self.link_bits.val()) << self.links_top.val());
        self.count_byte.next = bit_cast::<8, 32>(self.s_tdata.val() >> 24);
        for i in 0..4 {
            self.byte_at[i].next = self.code_byte.q.val() + self.byte_offset[i].val();
        }
    },
    node_record: {
        bit_cast::<NW, HB>(self.head.q.val())
            | (bit_cast::<NW, LB>(self.links_next.val()) << self.at_links.val())
    },
    header_counts: {
        self.last.d.next = self.image_end.val();
    },
    header_root: {
        // The root is node 0: (0, 0), which with N = 0 only an empty scene has.
        if (self.word.q.val() == 4) & self.s_tdata.val().any() {
            self.check.next = self.e_node_link.val();
        }
        if (self.word.q.val() == 5)
            & (self.s_tdata.val().any() | (!self.n.q.val().any() & self.t.q.val().any()))
        {
            self.check.next = self.e_node_link.val();
        }
    },
    header_tail: {
        if (self.word.q.val() == 13) & (self.s_tdata.val() != self.width.val()) {
            self.check.next = self.e_width.val();
        }
        if (self.word.q.val() >= 14) & self.s_tdata.val().any() {
            self.check.next = self.e_reserved.val();
        }
    },
    nodes: {
        self.k.d.next = self.k.q.val() + 1;
        if self.k.q.val() <= self.head_end.val() {
            self.head.d.next = (self.head.q.val() >> 32)
                | (bit_cast::<HB, 32>(self.s_tdata.val()) << self.head_top.val());
        } else {
            self.links.d.next = self.links_next.val();
            self.slot.d.next = self.slot.q.val() + 1;
            // Slots beyond the count hold 0; the others link in range.
            if self.slot.q.val() >= self.node_children.q.val() {
                if self.s_tdata.val().any() {
                    self.check.next = self.e_reserved.val();
                }
            } else if !self.link_count.val().any() {
                if self.link_first.val() >= self.n.q.val() {
                    self.check.next = self.e_node_link.val();
                }
            } else if self.leaf_end.val() > bit_cast::<33, 32>(self.t.q.val()) {
                self.check.next = self.e_leaf_link.val();
            }
        }
        if self.k.q.val() == 3 {
            self.node_children.d.next = self.count_byte.val();
            self.code_bytes.d.next =
                (self.count_byte.val() << 2) + (self.count_byte.val() << 1);
            self.code_byte.d.next = 0.into();
            if !self.count_byte.val().any()
                | (self.count_byte.val() > self.max_children.val())
            {
                self.check.next = self.e_child_count.val();
            }
        }
        // Code words: the bytes beyond the children's hold 0.
        if (self.k.q.val() > 3) & (self.k.q.val() <= self.head_end.val()) {
            self.code_byte.d.next = self.code_byte.q.val() + 4;
            for i in 0..4 {
                if (self.byte_at[i].val() >= self.code_bytes.q.val())
                    & self.s_tdata.val().get_bits::<8>(8 * i).any()
                {
                    self.check.next = self.e_reserved.val();
                }
            }
        }
        if self.k.q.val() == self.head_end.val() {
            self.slot.d.next = 0.into();
        }
        if self.k.q.val() == self.node_end.val() {
            self.node_ram.write_enable.next = true;
            self.k.d.next = 0.into();
            self.record.d.next = self.next_record.val();
            if self.next_record.val() == self.n.q.val() {
                self.record.d.next = 0.into();
                self.state.d.next = self.s_triangles.val();
            }
        }
    },
    links: {},
    root_outputs: {},
    node_fields: {
        self.origin[0].next = self.node_read.val().get_bits::<32>(0);
        self.origin[1].next = self.node_read.val().get_bits::<32>(32);
        self.origin[2].next = self.node_read.val().get_bits::<32>(64);
        self.exp[0].next = self.node_read.val().get_bits::<8>(96);
        self.exp[1].next = self.node_read.val().get_bits::<8>(104);
        self.exp[2].next = self.node_read.val().get_bits::<8>(112);
        self.children.next = self.node_read.val().get_bits::<4>(120);
        for c in 0..self.link.len() {
            for a in 0..3 {
                self.lo[3 * c + a].next = self.node_read.val().get_bits::<8>(128 + 48 * c + 8 * a);
                self.hi[3 * c + a].next = self.node_read.val().get_bits::<8>(152 + 48 * c + 8 * a);
            }
            self.link_read[c].next = self.node_read.val() >> self.link_at[c].val();
            self.link[c].next = self.link_read[c].val().get_bits::<LK>(0);
        }
    },
}

/// The memory of `$k`-wide nodes at `$nb` node and `$tb` triangle address bits, every width
/// parameter computed.
macro_rules! wide_memory_sized {
    ($k:literal, $nb:literal, $tb:literal) => {
        WideSceneMemory<
            $nb,
            $tb,
            { link_first_bits($nb, $tb) },
            { wide_link_bits($nb, $tb) },
            { wide_head_bits($k) },
            { $k * wide_link_bits($nb, $tb) },
            { wide_node_record_bits($k, $nb, $tb) },
            { triangle_record_bits() },
        >
    };
}

/// Memories for the small test images (16 nodes, 32 triangles).
pub type WideSceneMemory4w4x5 = wide_memory_sized!(4, 4, 5);
pub type WideSceneMemory8w4x5 = wide_memory_sized!(8, 4, 5);
/// 8-wide nodes on the XC7Z020: 2,048 nodes, 8,192 triangles (every thesis scene but All
/// materials whole).
pub type WideSceneMemory8w11x13 = wide_memory_sized!(8, 11, 13);

impl<
        const NB: usize,
        const TB: usize,
        const LF: usize,
        const LK: usize,
        const HB: usize,
        const LB: usize,
        const NW: usize,
        const TW: usize,
    > WideSceneMemory<NB, TB, LF, LK, HB, LB, NW, TW>
{
    /// A memory of `width`-child nodes with `triangle_ports` triangle read ports (at least
    /// one). Panics when a width parameter is not the one derived from `width`, `NB`, `TB`.
    pub fn new(width: usize, triangle_ports: usize) -> Self {
        assert!(
            WIDTHS.contains(&width),
            "a wide scene memory for {width} children: it is built for {WIDTHS:?}"
        );
        assert!(
            triangle_ports >= 1,
            "a scene memory needs a triangle read port"
        );
        let (nodes, triangles) = capacity_for(NB, TB);
        assert!(
            NB < 28 && TB < 28,
            "{NB}/{TB} address bits: a link's first has 28"
        );
        let want = [
            ("LF", LF, link_first_bits(NB, TB)),
            ("LK", LK, wide_link_bits(NB, TB)),
            ("HB", HB, wide_head_bits(width)),
            ("LB", LB, width * wide_link_bits(NB, TB)),
            ("NW", NW, wide_node_record_bits(width, NB, TB)),
            ("TW", TW, triangle_record_bits()),
        ];
        for (name, got, want) in want {
            assert_eq!(
                got, want,
                "{name} for {width}-wide nodes, {NB} node and {TB} triangle address bits"
            );
        }
        let words = node_words(width);
        assert!(words < 1 << NODE_WORDS_BITS);
        let head_words = words - width;
        let c32 = |x: usize| Constant::new((x as u64).into());
        let c16 = |x: usize| Constant::new((x as u64).into());
        let c8 = |x: usize| Constant::new((x as u64).into());
        let c5 = |x: usize| Constant::new((x as u64).into());
        scene_memory_new!(triangle_ports, nodes, triangles, {
            origin: Default::default(),
            exp: Default::default(),
            children: Default::default(),
            lo: defaults(3 * width),
            hi: defaults(3 * width),
            link: defaults(width),
            head: Default::default(),
            links: Default::default(),
            node_children: Default::default(),
            code_bytes: Default::default(),
            code_byte: Default::default(),
            slot: Default::default(),
            version: Constant::new(u64::from(VERSION_WIDE).into()),
            width: c32(width),
            max_children: c8(width),
            node_words_mask: (0..NODE_WORDS_BITS)
                .map(|s| {
                    let set = words >> s & 1 == 1;
                    Constant::new(if set { u64::from(u32::MAX) } else { 0 }.into())
                })
                .collect(),
            node_words_shift: (0..NODE_WORDS_BITS).map(c8).collect(),
            byte_offset: (0..4).map(c8).collect(),
            head_top: c16(HB - 32),
            links_top: c16(LB - LK),
            link_size: c16(LK),
            first_mask: c32((1 << hw_model::traversal::wide::image::FIRST_BITS) - 1),
            at_count: c16(LF),
            at_links: c16(HB),
            link_at: (0..width).map(|c| c16(HB + c * LK)).collect(),
            head_end: c5(head_words - 1),
            node_end: c5(words - 1),
            triangle_end: c5(TRIANGLE_WORDS - 1),
            e_width: code(LoadError::Width),
            e_child_count: code(LoadError::ChildCount),
            image_end: Default::default(),
            link_first: Default::default(),
            link_count: Default::default(),
            link_bits: Default::default(),
            links_next: Default::default(),
            byte_at: defaults(4),
            count_byte: Default::default(),
            link_read: defaults(width),
        })
    }
}
