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

use super::scene_memory::{code, LoadState, STATE_BITS};
use super::scene_records::*;
use super::wide::{Code, Count};
use crate::defaults;
use hw_model::traversal::scene_image::{HEADER_WORDS, MAGIC, TRIANGLE_WORDS, VERSION_WIDE};
use hw_model::traversal::wide::image::node_words;
use hw_model::traversal::wide::WIDTHS;

/// Bits of the image's words per node ([`node_words`], at most 24), so of `last`'s
/// shift-and-add multiply.
const NODE_WORDS_BITS: usize = 5;

#[derive(LogicBlock)]
pub struct WideSceneMemory<
    const NB: usize,
    const TB: usize,
    const LF: usize,
    const LK: usize,
    const HB: usize,
    const LB: usize,
    const NW: usize,
    const TW: usize,
> {
    pub clock: Signal<In, Clock>,
    /// Starts a load (any state): the next stream word is the image's word 0.
    pub start_load: Signal<In, Bit>,
    pub s_tdata: Signal<In, Bits<32>>,
    pub s_tvalid: Signal<In, Bit>,
    pub s_tlast: Signal<In, Bit>,
    pub s_tready: Signal<Out, Bit>,
    pub loading: Signal<Out, Bit>,
    pub loaded: Signal<Out, Bit>,
    pub error: Signal<Out, Bit>,
    /// A [`LoadError`] code, 0 while there is none.
    pub error_code: Signal<Out, Bits<ERROR_CODE_BITS>>,
    /// The stream index of the word that showed the error, and that word.
    pub error_word: Signal<Out, Bits<32>>,
    pub error_value: Signal<Out, Bits<32>>,
    /// N and T of the image (valid once the header has passed); N = 0: an empty scene.
    pub nodes: Signal<Out, Bits<32>>,
    pub triangles: Signal<Out, Bits<32>>,
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
    /// Triangle read ports (one per MT lane), as the binary memory's.
    pub triangle_address: Vec<Signal<In, Bits<TB>>>,
    pub vertices: Vec<Signal<Out, Bits<VERTEX_BITS>>>,
    pub global_index: Vec<Signal<Out, Bits<INDEX_BITS>>>,
    pub casts_shadow: Vec<Signal<Out, Bit>>,
    node_ram: RAM<Bits<NW>, NB>,
    /// One copy of the triangles per read port (rust-hdl's `RAM` has one read port).
    triangle_ram: Vec<RAM<Bits<TW>, TB>>,
    state: DFF<Bits<STATE_BITS>>,
    /// Stream index of the next word, and of the image's last word (from the header).
    word: DFF<Bits<32>>,
    last: DFF<Bits<32>>,
    /// Word within the current record, and the record's index.
    k: DFF<Bits<5>>,
    record: DFF<Bits<32>>,
    n: DFF<Bits<32>>,
    t: DFF<Bits<32>>,
    /// The previous word (a triangle's flags when its reserved word arrives).
    prev: DFF<Bits<32>>,
    /// The node being assembled: its head words shift in from the top, then its links.
    head: DFF<Bits<HB>>,
    links: DFF<Bits<LB>>,
    /// The node's child count, 6 × it (its code bytes), the first byte of this code word,
    /// the slot of this link word.
    node_children: DFF<Bits<8>>,
    code_bytes: DFF<Bits<8>>,
    code_byte: DFF<Bits<8>>,
    slot: DFF<Bits<8>>,
    verts: DFF<Bits<VERTEX_BITS>>,
    index: DFF<Bits<INDEX_BITS>>,
    /// The scene's triangle count S (header word 12).
    scene_triangles: DFF<Bits<32>>,
    error_code_reg: DFF<Bits<ERROR_CODE_BITS>>,
    error_word_reg: DFF<Bits<32>>,
    error_value_reg: DFF<Bits<32>>,
    s_header: Constant<Bits<STATE_BITS>>,
    s_nodes: Constant<Bits<STATE_BITS>>,
    s_triangles: Constant<Bits<STATE_BITS>>,
    s_loaded: Constant<Bits<STATE_BITS>>,
    s_drain: Constant<Bits<STATE_BITS>>,
    s_failed: Constant<Bits<STATE_BITS>>,
    magic: Constant<Bits<32>>,
    version: Constant<Bits<32>>,
    /// K, as header word 13 and a child count compare with it.
    width: Constant<Bits<32>>,
    max_children: Constant<Bits<8>>,
    max_nodes: Constant<Bits<32>>,
    max_triangles: Constant<Bits<32>>,
    max_scene_triangles: Constant<Bits<32>>,
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
    at_flag: Constant<Bits<16>>,
    at_index: Constant<Bits<16>>,
    /// The image's last header word; a node's last head word and last word; a triangle's
    /// last word.
    header_end: Constant<Bits<32>>,
    head_end: Constant<Bits<5>>,
    node_end: Constant<Bits<5>>,
    triangle_end: Constant<Bits<5>>,
    e_magic: Constant<Bits<ERROR_CODE_BITS>>,
    e_version: Constant<Bits<ERROR_CODE_BITS>>,
    e_nodes: Constant<Bits<ERROR_CODE_BITS>>,
    e_triangles: Constant<Bits<ERROR_CODE_BITS>>,
    e_node_link: Constant<Bits<ERROR_CODE_BITS>>,
    e_leaf_link: Constant<Bits<ERROR_CODE_BITS>>,
    e_index: Constant<Bits<ERROR_CODE_BITS>>,
    e_flags: Constant<Bits<ERROR_CODE_BITS>>,
    e_reserved: Constant<Bits<ERROR_CODE_BITS>>,
    e_early_last: Constant<Bits<ERROR_CODE_BITS>>,
    e_missing_last: Constant<Bits<ERROR_CODE_BITS>>,
    e_scene_triangles: Constant<Bits<ERROR_CODE_BITS>>,
    e_width: Constant<Bits<ERROR_CODE_BITS>>,
    e_child_count: Constant<Bits<ERROR_CODE_BITS>>,
    /// A beat is taken this cycle.
    take: Signal<Local, Bit>,
    /// The error this word shows (0: none).
    check: Signal<Local, Bits<ERROR_CODE_BITS>>,
    /// This word is the image's last.
    is_last: Signal<Local, Bit>,
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
    next_record: Signal<Local, Bits<32>>,
    node_read: Signal<Local, Bits<NW>>,
    /// The read record shifted to each slot's link.
    link_read: Vec<Signal<Local, Bits<NW>>>,
    triangle_write: Signal<Local, Bit>,
    triangle_record: Signal<Local, Bits<TW>>,
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
        Self {
            clock: Default::default(),
            start_load: Default::default(),
            s_tdata: Default::default(),
            s_tvalid: Default::default(),
            s_tlast: Default::default(),
            s_tready: Default::default(),
            loading: Default::default(),
            loaded: Default::default(),
            error: Default::default(),
            error_code: Default::default(),
            error_word: Default::default(),
            error_value: Default::default(),
            nodes: Default::default(),
            triangles: Default::default(),
            node_address: Default::default(),
            origin: Default::default(),
            exp: Default::default(),
            children: Default::default(),
            lo: defaults(3 * width),
            hi: defaults(3 * width),
            link: defaults(width),
            triangle_address: defaults(triangle_ports),
            vertices: defaults(triangle_ports),
            global_index: defaults(triangle_ports),
            casts_shadow: defaults(triangle_ports),
            node_ram: Default::default(),
            triangle_ram: defaults(triangle_ports),
            state: Default::default(),
            word: Default::default(),
            last: Default::default(),
            k: Default::default(),
            record: Default::default(),
            n: Default::default(),
            t: Default::default(),
            prev: Default::default(),
            head: Default::default(),
            links: Default::default(),
            node_children: Default::default(),
            code_bytes: Default::default(),
            code_byte: Default::default(),
            slot: Default::default(),
            verts: Default::default(),
            index: Default::default(),
            scene_triangles: Default::default(),
            error_code_reg: Default::default(),
            error_word_reg: Default::default(),
            error_value_reg: Default::default(),
            s_header: LoadState::Header.constant(),
            s_nodes: LoadState::Nodes.constant(),
            s_triangles: LoadState::Triangles.constant(),
            s_loaded: LoadState::Loaded.constant(),
            s_drain: LoadState::Drain.constant(),
            s_failed: LoadState::Failed.constant(),
            magic: Constant::new(u64::from(MAGIC).into()),
            version: Constant::new(u64::from(VERSION_WIDE).into()),
            width: c32(width),
            max_children: c8(width),
            max_nodes: c32(nodes),
            max_triangles: c32(triangles),
            max_scene_triangles: c32(1 << INDEX_BITS),
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
            at_flag: c16(VERTEX_BITS),
            at_index: c16(VERTEX_BITS + 1),
            header_end: c32(HEADER_WORDS - 1),
            head_end: c5(head_words - 1),
            node_end: c5(words - 1),
            triangle_end: c5(TRIANGLE_WORDS - 1),
            e_magic: code(LoadError::BadMagic),
            e_version: code(LoadError::BadVersion),
            e_nodes: code(LoadError::TooManyNodes),
            e_triangles: code(LoadError::TooManyTriangles),
            e_node_link: code(LoadError::NodeLink),
            e_leaf_link: code(LoadError::LeafLink),
            e_index: code(LoadError::GlobalIndex),
            e_flags: code(LoadError::BadFlags),
            e_reserved: code(LoadError::Reserved),
            e_early_last: code(LoadError::EarlyLast),
            e_missing_last: code(LoadError::MissingLast),
            e_scene_triangles: code(LoadError::SceneTriangles),
            e_width: code(LoadError::Width),
            e_child_count: code(LoadError::ChildCount),
            take: Default::default(),
            check: Default::default(),
            is_last: Default::default(),
            image_end: Default::default(),
            link_first: Default::default(),
            link_count: Default::default(),
            leaf_end: Default::default(),
            link_bits: Default::default(),
            links_next: Default::default(),
            byte_at: defaults(4),
            count_byte: Default::default(),
            next_record: Default::default(),
            node_read: Default::default(),
            link_read: defaults(width),
            triangle_write: Default::default(),
            triangle_record: Default::default(),
        }
    }
}

impl<
        const NB: usize,
        const TB: usize,
        const LF: usize,
        const LK: usize,
        const HB: usize,
        const LB: usize,
        const NW: usize,
        const TW: usize,
    > Logic for WideSceneMemory<NB, TB, LF, LK, HB, LB, NW, TW>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            state,
            word,
            last,
            k,
            record,
            n,
            t,
            prev,
            head,
            links,
            node_children,
            code_bytes,
            code_byte,
            slot,
            verts,
            index,
            scene_triangles,
            error_code_reg,
            error_word_reg,
            error_value_reg
        );
        self.node_ram.read_clock.next = self.clock.val();
        self.node_ram.write_clock.next = self.clock.val();
        for p in 0..self.triangle_ram.len() {
            self.triangle_ram[p].read_clock.next = self.clock.val();
            self.triangle_ram[p].write_clock.next = self.clock.val();
        }

        self.s_tready.next = ((self.state.q.val() == self.s_header.val())
            | (self.state.q.val() == self.s_nodes.val())
            | (self.state.q.val() == self.s_triangles.val())
            | (self.state.q.val() == self.s_drain.val()))
            & !self.start_load.val();
        self.take.next = self.s_tready.val() & self.s_tvalid.val();
        self.is_last.next = self.word.q.val() == self.last.q.val();
        self.check.next = 0.into();
        self.next_record.next = self.record.q.val() + 1;
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

        // A node is written with its last link word, a triangle with its reserved word.
        self.node_ram.write_enable.next = false;
        self.node_ram.write_address.next = bit_cast::<NB, 32>(self.record.q.val());
        self.node_ram.write_data.next = bit_cast::<NW, HB>(self.head.q.val())
            | (bit_cast::<NW, LB>(self.links_next.val()) << self.at_links.val());
        self.triangle_write.next = false;
        self.triangle_record.next = bit_cast::<TW, VERTEX_BITS>(self.verts.q.val())
            | (bit_cast::<TW, 1>(bit_cast::<1, 32>(self.prev.q.val())) << self.at_flag.val())
            | (bit_cast::<TW, INDEX_BITS>(self.index.q.val()) << self.at_index.val());

        if self.take.val() {
            self.word.d.next = self.word.q.val() + 1;
            self.prev.d.next = self.s_tdata.val();
            if self.state.q.val() == self.s_header.val() {
                if (self.word.q.val() == 0) & (self.s_tdata.val() != self.magic.val()) {
                    self.check.next = self.e_magic.val();
                }
                if (self.word.q.val() == 1) & (self.s_tdata.val() != self.version.val()) {
                    self.check.next = self.e_version.val();
                }
                if self.word.q.val() == 2 {
                    self.n.d.next = self.s_tdata.val();
                    if self.s_tdata.val() > self.max_nodes.val() {
                        self.check.next = self.e_nodes.val();
                    }
                }
                if self.word.q.val() == 3 {
                    self.t.d.next = self.s_tdata.val();
                    self.last.d.next = self.image_end.val();
                    if self.s_tdata.val() > self.max_triangles.val() {
                        self.check.next = self.e_triangles.val();
                    }
                }
                // The root is node 0: (0, 0), which with N = 0 only an empty scene has.
                if (self.word.q.val() == 4) & self.s_tdata.val().any() {
                    self.check.next = self.e_node_link.val();
                }
                if (self.word.q.val() == 5)
                    & (self.s_tdata.val().any() | (!self.n.q.val().any() & self.t.q.val().any()))
                {
                    self.check.next = self.e_node_link.val();
                }
                if self.word.q.val() == 12 {
                    self.scene_triangles.d.next = self.s_tdata.val();
                    if (self.s_tdata.val() < self.t.q.val())
                        | (self.s_tdata.val() > self.max_scene_triangles.val())
                    {
                        self.check.next = self.e_scene_triangles.val();
                    }
                }
                if (self.word.q.val() == 13) & (self.s_tdata.val() != self.width.val()) {
                    self.check.next = self.e_width.val();
                }
                if (self.word.q.val() >= 14) & self.s_tdata.val().any() {
                    self.check.next = self.e_reserved.val();
                }
                if self.word.q.val() == self.header_end.val() {
                    self.k.d.next = 0.into();
                    self.record.d.next = 0.into();
                    if self.n.q.val().any() {
                        self.state.d.next = self.s_nodes.val();
                    } else {
                        self.state.d.next = self.s_triangles.val();
                    }
                }
            } else if self.state.q.val() == self.s_nodes.val() {
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
            } else if self.state.q.val() == self.s_triangles.val() {
                self.k.d.next = self.k.q.val() + 1;
                if self.k.q.val() < 9 {
                    self.verts.d.next = (self.verts.q.val() >> 32)
                        | (bit_cast::<VERTEX_BITS, 32>(self.s_tdata.val()) << 256);
                }
                if self.k.q.val() == 9 {
                    self.index.d.next = bit_cast::<INDEX_BITS, 32>(self.s_tdata.val());
                    if self.s_tdata.val() >= self.scene_triangles.q.val() {
                        self.check.next = self.e_index.val();
                    }
                }
                if (self.k.q.val() == 10) & (self.s_tdata.val() >> 1).any() {
                    self.check.next = self.e_flags.val();
                }
                if self.k.q.val() == self.triangle_end.val() {
                    if self.s_tdata.val().any() {
                        self.check.next = self.e_reserved.val();
                    }
                    self.triangle_write.next = true;
                    self.k.d.next = 0.into();
                    self.record.d.next = self.next_record.val();
                }
            }
            if self.state.q.val() == self.s_drain.val() {
                if self.s_tlast.val() {
                    self.state.d.next = self.s_failed.val();
                }
            } else {
                if self.check.val().any() {
                    self.error_code_reg.d.next = self.check.val();
                    self.error_word_reg.d.next = self.word.q.val();
                    self.error_value_reg.d.next = self.s_tdata.val();
                    self.state.d.next = self.s_drain.val();
                    if self.s_tlast.val() {
                        self.state.d.next = self.s_failed.val();
                    }
                } else if self.s_tlast.val() & !self.is_last.val() {
                    self.error_code_reg.d.next = self.e_early_last.val();
                    self.error_word_reg.d.next = self.word.q.val();
                    self.error_value_reg.d.next = self.s_tdata.val();
                    self.state.d.next = self.s_failed.val();
                } else if self.is_last.val() & !self.s_tlast.val() {
                    self.error_code_reg.d.next = self.e_missing_last.val();
                    self.error_word_reg.d.next = self.word.q.val();
                    self.error_value_reg.d.next = self.s_tdata.val();
                    self.state.d.next = self.s_drain.val();
                } else if self.is_last.val() {
                    self.state.d.next = self.s_loaded.val();
                }
            }
        }
        if self.start_load.val() {
            self.state.d.next = self.s_header.val();
            self.word.d.next = 0.into();
            self.last.d.next = self.header_end.val();
            self.error_code_reg.d.next = 0.into();
            self.error_word_reg.d.next = 0.into();
            self.error_value_reg.d.next = 0.into();
        }

        self.loading.next = (self.state.q.val() == self.s_header.val())
            | (self.state.q.val() == self.s_nodes.val())
            | (self.state.q.val() == self.s_triangles.val());
        self.loaded.next = self.state.q.val() == self.s_loaded.val();
        self.error.next = self.error_code_reg.q.val().any();
        self.error_code.next = self.error_code_reg.q.val();
        self.error_word.next = self.error_word_reg.q.val();
        self.error_value.next = self.error_value_reg.q.val();
        self.nodes.next = self.n.q.val();
        self.triangles.next = self.t.q.val();

        self.node_ram.read_address.next = self.node_address.val();
        self.node_read.next = self.node_ram.read_data.val();
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

        for p in 0..self.triangle_ram.len() {
            self.triangle_ram[p].write_enable.next = self.triangle_write.val();
            self.triangle_ram[p].write_address.next = bit_cast::<TB, 32>(self.record.q.val());
            self.triangle_ram[p].write_data.next = self.triangle_record.val();
            self.triangle_ram[p].read_address.next = self.triangle_address[p].val();
            self.vertices[p].next = self.triangle_ram[p]
                .read_data
                .val()
                .get_bits::<VERTEX_BITS>(0);
            self.casts_shadow[p].next = self.triangle_ram[p].read_data.val().get_bit(288);
            self.global_index[p].next = self.triangle_ram[p]
                .read_data
                .val()
                .get_bits::<INDEX_BITS>(289);
        }
    }
}
