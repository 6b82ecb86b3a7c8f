//! The traversal unit's scene memory: the scene image (`docs/scene-image.md`) in two block
//! RAMs, one BVH node and one triangle per word, filled by a checking loader from an
//! AXI4-Stream of 32-bit words.
//!
//! Its records, capacity and load errors: [`super::scene_records`] (re-exported here).
//!
//! The loader (`start_load`, then the stream): the header, N nodes and T triangles in image
//! order, each record written when its last word arrives. It checks what is cheap in
//! hardware as the words pass: magic and version, N and T against this memory's capacity, every
//! link (a node link below N, a leaf within T; the root too), the scene's triangle count S
//! (T ≤ S ≤ 2^[`INDEX_BITS`]), each global index below S, flags
//! other than bit 0, reserved words other than 0, and `tlast` exactly on the image's last word.
//! The first failure stops the load with a [`LoadError`] code, the index of the word that showed
//! it and that word. What needs the whole tree (a cycle or a shared subtree, duplicate global
//! indices) is not checked here: the driver runs `SceneImage::from_words` before streaming
//! (`scene_memory_driver`).
//!
//! `s_tready`: low while idle, loaded or failed (a stream sent without `start_load` waits); high
//! every cycle from `start_load` until the beat with `tlast`, including after an error, whose
//! remaining words are drained (dropped) so that a DMA never stalls on a refused image. It is
//! low in the cycle of `start_load`, which restarts any load and replaces the scene.
//!
//! Read ports: an address in, the record's fields out one cycle later (block RAM read latency).
//!
//! Resources at three capacities (yosys xc7): docs/scene-image.md, "Scene memory in block RAM".
//!
//! rust-hdl cannot derive widths: `NB`, `TB` address bits (capacity 2^NB nodes, 2^TB
//! triangles, [`capacity_for`]), `LF`, `LC` link widths, `NW`, `TW` record widths, all checked
//! by [`SceneMemory::new`]; the aliases below fix them per configuration.

use rust_hdl::prelude::*;

pub use super::scene_records::*;
use crate::defaults;
use hw_model::traversal::scene_image::{HEADER_WORDS, MAGIC, NODE_WORDS, TRIANGLE_WORDS, VERSION};

/// A load error's code, as the kernel compares it.
pub(super) fn code(error: LoadError) -> Constant<Bits<ERROR_CODE_BITS>> {
    Constant::new(error.code().into())
}

/// The loader's states, as the `state` register's values (a `Bits` register with constants:
/// rust-hdl's `LogicState` enums leave unused parameters that fail Verilator's lint).
#[derive(Copy, Clone, Debug, PartialEq)]
#[repr(u8)]
pub(super) enum LoadState {
    Idle,
    Header,
    Nodes,
    Triangles,
    Loaded,
    /// Refused; the rest of the packet is dropped up to its `tlast`.
    Drain,
    /// Refused, packet over.
    Failed,
}

/// Width of the `state` register.
pub(super) const STATE_BITS: usize = 3;

// Power-up: the `state` register starts at 0, idle.
const _: () = assert!(LoadState::Idle as u8 == 0);

impl LoadState {
    pub(super) fn constant(self) -> Constant<Bits<STATE_BITS>> {
        Constant::new((self as u64).into())
    }
}

/// The scene memory's block, the same for the binary memory and the wide one
/// (`wide_scene_memory::WideSceneMemory`): the stream protocol, the loader's states, the header's
/// and the triangles' checks, `tlast`, the status outputs and the triangle read ports. Each memory
/// says its node records: the fields it adds (`node_ports`, `node_registers`, `format_constants`,
/// `node_constants`, `record_ends`, `format_errors`, `word_signals`, `node_signals`,
/// `read_signals`, each where the binary memory has them), `record_word_bits` the width of the
/// word-in-record counter, and the statements: its registers (`node_dffs`), what each word computes
/// (`each_word`), the node record written (`node_record`), `last` from header word 3
/// (`header_counts`), its header words around the root (`header_root`) and after S (`header_tail`),
/// the node words (`nodes`), checks after a record's word (`links`), root outputs (`root_outputs`)
/// and the node read's fields (`node_fields`). A macro rather than a shared sub-block, which would
/// change the binary unit's Verilog; `self` and `#[hdl_gen]` come from the caller (macro hygiene:
/// the attribute's `connect` takes the caller's `self`), as do the statements that use `self`.
macro_rules! scene_memory_block {
    (
        $pound:tt $hdl_gen:tt
        $this:ident,
        $memory:ident<$($g:ident),*>,
        record_word_bits: $kb:tt,
        node_ports: { $($node_ports:tt)* },
        node_registers: { $($node_registers:tt)* },
        format_constants: { $($format_constants:tt)* },
        node_constants: { $($node_constants:tt)* },
        record_ends: { $($record_ends:tt)* },
        format_errors: { $($format_errors:tt)* },
        word_signals: { $($word_signals:tt)* },
        node_signals: { $($node_signals:tt)* },
        read_signals: { $($read_signals:tt)* },
        node_dffs: { $($node_dffs:tt)* },
        each_word: { $($each_word:tt)* },
        node_record: { $($node_record:tt)* },
        header_counts: { $($header_counts:tt)* },
        header_root: { $($header_root:tt)* },
        header_tail: { $($header_tail:tt)* },
        nodes: { $($nodes:tt)* },
        links: { $($links:tt)* },
        root_outputs: { $($root_outputs:tt)* },
        node_fields: { $($node_fields:tt)* },
    ) => {
        #[derive(LogicBlock)]
        pub struct $memory<$(const $g: usize),*> {
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
            /// N and T of the image (valid once the header has passed).
            pub nodes: Signal<Out, Bits<32>>,
            pub triangles: Signal<Out, Bits<32>>,
            $($node_ports)*
            /// Triangle read ports (one per MT lane): port p's record at `triangle_address[p]`,
            /// one cycle later.
            pub triangle_address: Vec<Signal<In, Bits<TB>>>,
            /// Port p's v0 x y z, v1 x y z, v2 x y z (word 0 lowest).
            pub vertices: Vec<Signal<Out, Bits<VERTEX_BITS>>>,
            pub global_index: Vec<Signal<Out, Bits<INDEX_BITS>>>,
            pub casts_shadow: Vec<Signal<Out, Bit>>,
            node_ram: RAM<Bits<NW>, NB>,
            /// One copy of the triangles per read port, all written by the loader: rust-hdl's `RAM`
            /// has one read port, so a second reader cannot use the block RAM's second port.
            triangle_ram: Vec<RAM<Bits<TW>, TB>>,
            state: DFF<Bits<STATE_BITS>>,
            /// Stream index of the next word, and of the image's last word (from the header).
            word: DFF<Bits<32>>,
            last: DFF<Bits<32>>,
            /// Word within the current record, and the record's index.
            k: DFF<Bits<$kb>>,
            record: DFF<Bits<32>>,
            n: DFF<Bits<32>>,
            t: DFF<Bits<32>>,
            /// The previous word (a link's first when its count arrives, a triangle's flags when its
            /// reserved word arrives).
            prev: DFF<Bits<32>>,
            $($node_registers)*
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
            $($format_constants)*
            /// The capacity, compared with N and T.
            max_nodes: Constant<Bits<32>>,
            max_triangles: Constant<Bits<32>>,
            max_scene_triangles: Constant<Bits<32>>,
            $($node_constants)*
            at_flag: Constant<Bits<16>>,
            at_index: Constant<Bits<16>>,
            /// The image's last header word, its last node word, its last triangle word.
            header_end: Constant<Bits<32>>,
            $($record_ends)*
            triangle_end: Constant<Bits<$kb>>,
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
            $($format_errors)*
            /// A beat is taken this cycle.
            take: Signal<Local, Bit>,
            /// The error this word shows (0: none).
            check: Signal<Local, Bits<ERROR_CODE_BITS>>,
            $($word_signals)*
            /// This word is the image's last.
            is_last: Signal<Local, Bit>,
            $($node_signals)*
            next_record: Signal<Local, Bits<32>>,
            node_read: Signal<Local, Bits<NW>>,
            $($read_signals)*
            /// The loader writes a triangle record (into every copy).
            triangle_write: Signal<Local, Bit>,
            triangle_record: Signal<Local, Bits<TW>>,
        }

        impl<$(const $g: usize),*> Logic for $memory<$($g),*> {
            $pound $hdl_gen
            fn update(&mut $this) {
                dff_setup!(
                    $this,
                    clock,
                    state,
                    word,
                    last,
                    k,
                    record,
                    n,
                    t,
                    prev,
                    $($node_dffs)*
                    verts,
                    index,
                    scene_triangles,
                    error_code_reg,
                    error_word_reg,
                    error_value_reg
                );
                $this.node_ram.read_clock.next = $this.clock.val();
                $this.node_ram.write_clock.next = $this.clock.val();
                for p in 0..$this.triangle_ram.len() {
                    $this.triangle_ram[p].read_clock.next = $this.clock.val();
                    $this.triangle_ram[p].write_clock.next = $this.clock.val();
                }

                $this.s_tready.next = (($this.state.q.val() == $this.s_header.val())
                    | ($this.state.q.val() == $this.s_nodes.val())
                    | ($this.state.q.val() == $this.s_triangles.val())
                    | ($this.state.q.val() == $this.s_drain.val()))
                    & !$this.start_load.val();
                $this.take.next = $this.s_tready.val() & $this.s_tvalid.val();
                $this.is_last.next = $this.word.q.val() == $this.last.q.val();
                $this.check.next = 0.into();
                $($each_word)*
                $this.next_record.next = $this.record.q.val() + 1;

                // A node is written with its last word (child 1's count), a triangle with its
                // reserved word; the record is what was gathered plus this word.
                $this.node_ram.write_enable.next = false;
                $this.node_ram.write_address.next = bit_cast::<NB, 32>($this.record.q.val());
                $this.node_ram.write_data.next = $($node_record)*;
                $this.triangle_write.next = false;
                $this.triangle_record.next = bit_cast::<TW, VERTEX_BITS>($this.verts.q.val())
                    | (bit_cast::<TW, 1>(bit_cast::<1, 32>($this.prev.q.val())) << $this.at_flag.val())
                    | (bit_cast::<TW, INDEX_BITS>($this.index.q.val()) << $this.at_index.val());

                if $this.take.val() {
                    $this.word.d.next = $this.word.q.val() + 1;
                    $this.prev.d.next = $this.s_tdata.val();
                    if $this.state.q.val() == $this.s_header.val() {
                        if ($this.word.q.val() == 0) & ($this.s_tdata.val() != $this.magic.val()) {
                            $this.check.next = $this.e_magic.val();
                        }
                        if ($this.word.q.val() == 1) & ($this.s_tdata.val() != $this.version.val()) {
                            $this.check.next = $this.e_version.val();
                        }
                        if $this.word.q.val() == 2 {
                            $this.n.d.next = $this.s_tdata.val();
                            if $this.s_tdata.val() > $this.max_nodes.val() {
                                $this.check.next = $this.e_nodes.val();
                            }
                        }
                        if $this.word.q.val() == 3 {
                            $this.t.d.next = $this.s_tdata.val();
                            $($header_counts)*
                            if $this.s_tdata.val() > $this.max_triangles.val() {
                                $this.check.next = $this.e_triangles.val();
                            }
                        }
                        $($header_root)*
                        if $this.word.q.val() == 12 {
                            $this.scene_triangles.d.next = $this.s_tdata.val();
                            if ($this.s_tdata.val() < $this.t.q.val())
                                | ($this.s_tdata.val() > $this.max_scene_triangles.val())
                            {
                                $this.check.next = $this.e_scene_triangles.val();
                            }
                        }
                        $($header_tail)*
                        if $this.word.q.val() == $this.header_end.val() {
                            $this.k.d.next = 0.into();
                            $this.record.d.next = 0.into();
                            if $this.n.q.val().any() {
                                $this.state.d.next = $this.s_nodes.val();
                            } else {
                                $this.state.d.next = $this.s_triangles.val();
                            }
                        }
                    } else if $this.state.q.val() == $this.s_nodes.val() {
                        $($nodes)*
                    } else if $this.state.q.val() == $this.s_triangles.val() {
                        $this.k.d.next = $this.k.q.val() + 1;
                        if $this.k.q.val() < 9 {
                            $this.verts.d.next = ($this.verts.q.val() >> 32)
                                | (bit_cast::<VERTEX_BITS, 32>($this.s_tdata.val()) << 256);
                        }
                        if $this.k.q.val() == 9 {
                            $this.index.d.next = bit_cast::<INDEX_BITS, 32>($this.s_tdata.val());
                            if $this.s_tdata.val() >= $this.scene_triangles.q.val() {
                                $this.check.next = $this.e_index.val();
                            }
                        }
                        if ($this.k.q.val() == 10) & ($this.s_tdata.val() >> 1).any() {
                            $this.check.next = $this.e_flags.val();
                        }
                        if $this.k.q.val() == $this.triangle_end.val() {
                            if $this.s_tdata.val().any() {
                                $this.check.next = $this.e_reserved.val();
                            }
                            $this.triangle_write.next = true;
                            $this.k.d.next = 0.into();
                            $this.record.d.next = $this.next_record.val();
                        }
                    }
                    $($links)*
                    if $this.state.q.val() == $this.s_drain.val() {
                        if $this.s_tlast.val() {
                            $this.state.d.next = $this.s_failed.val();
                        }
                    } else {
                        if $this.check.val().any() {
                            $this.error_code_reg.d.next = $this.check.val();
                            $this.error_word_reg.d.next = $this.word.q.val();
                            $this.error_value_reg.d.next = $this.s_tdata.val();
                            $this.state.d.next = $this.s_drain.val();
                            if $this.s_tlast.val() {
                                $this.state.d.next = $this.s_failed.val();
                            }
                        } else if $this.s_tlast.val() & !$this.is_last.val() {
                            $this.error_code_reg.d.next = $this.e_early_last.val();
                            $this.error_word_reg.d.next = $this.word.q.val();
                            $this.error_value_reg.d.next = $this.s_tdata.val();
                            $this.state.d.next = $this.s_failed.val();
                        } else if $this.is_last.val() & !$this.s_tlast.val() {
                            $this.error_code_reg.d.next = $this.e_missing_last.val();
                            $this.error_word_reg.d.next = $this.word.q.val();
                            $this.error_value_reg.d.next = $this.s_tdata.val();
                            $this.state.d.next = $this.s_drain.val();
                        } else if $this.is_last.val() {
                            $this.state.d.next = $this.s_loaded.val();
                        }
                    }
                }
                if $this.start_load.val() {
                    $this.state.d.next = $this.s_header.val();
                    $this.word.d.next = 0.into();
                    $this.last.d.next = $this.header_end.val();
                    $this.error_code_reg.d.next = 0.into();
                    $this.error_word_reg.d.next = 0.into();
                    $this.error_value_reg.d.next = 0.into();
                }

                $this.loading.next = ($this.state.q.val() == $this.s_header.val())
                    | ($this.state.q.val() == $this.s_nodes.val())
                    | ($this.state.q.val() == $this.s_triangles.val());
                $this.loaded.next = $this.state.q.val() == $this.s_loaded.val();
                $this.error.next = $this.error_code_reg.q.val().any();
                $this.error_code.next = $this.error_code_reg.q.val();
                $this.error_word.next = $this.error_word_reg.q.val();
                $this.error_value.next = $this.error_value_reg.q.val();
                $this.nodes.next = $this.n.q.val();
                $this.triangles.next = $this.t.q.val();
                $($root_outputs)*

                $this.node_ram.read_address.next = $this.node_address.val();
                $this.node_read.next = $this.node_ram.read_data.val();
                $($node_fields)*
                for p in 0..$this.triangle_ram.len() {
                    $this.triangle_ram[p].write_enable.next = $this.triangle_write.val();
                    $this.triangle_ram[p].write_address.next = bit_cast::<TB, 32>($this.record.q.val());
                    $this.triangle_ram[p].write_data.next = $this.triangle_record.val();
                    $this.triangle_ram[p].read_address.next = $this.triangle_address[p].val();
                    // The record's fields at their bits (`bit_cast` cannot take a loop index).
                    $this.vertices[p].next = $this.triangle_ram[p]
                        .read_data
                        .val()
                        .get_bits::<VERTEX_BITS>(0);
                    $this.casts_shadow[p].next = $this.triangle_ram[p].read_data.val().get_bit(288);
                    $this.global_index[p].next = $this.triangle_ram[p]
                        .read_data
                        .val()
                        .get_bits::<INDEX_BITS>(289);
                }
            }
        }
    };
}
pub(crate) use scene_memory_block;

/// The struct literal of a scene memory (`scene_memory_block!`'s) with `triangle_ports`
/// triangle read ports and a capacity of `nodes` and `triangles`: the shared fields' values
/// (status, loader registers, states, the header's and the triangles' constants and error
/// codes), then the memory's own (`own`).
macro_rules! scene_memory_new {
    ($triangle_ports:expr, $nodes:expr, $triangles:expr, { $($own:tt)* }) => {
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
            triangle_address: defaults($triangle_ports),
            vertices: defaults($triangle_ports),
            global_index: defaults($triangle_ports),
            casts_shadow: defaults($triangle_ports),
            node_ram: Default::default(),
            triangle_ram: defaults($triangle_ports),
            state: Default::default(),
            word: Default::default(),
            last: Default::default(),
            k: Default::default(),
            record: Default::default(),
            n: Default::default(),
            t: Default::default(),
            prev: Default::default(),
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
            max_nodes: Constant::new(($nodes as u64).into()),
            max_triangles: Constant::new(($triangles as u64).into()),
            max_scene_triangles: Constant::new(((1 << INDEX_BITS) as u64).into()),
            at_flag: Constant::new((VERTEX_BITS as u64).into()),
            at_index: Constant::new(((VERTEX_BITS + 1) as u64).into()),
            header_end: Constant::new(((HEADER_WORDS - 1) as u64).into()),
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
            take: Default::default(),
            check: Default::default(),
            is_last: Default::default(),
            leaf_end: Default::default(),
            next_record: Default::default(),
            node_read: Default::default(),
            triangle_write: Default::default(),
            triangle_record: Default::default(),
            $($own)*
        }
    };
}
pub(crate) use scene_memory_new;

scene_memory_block! {
    #[hdl_gen]
    self,
    SceneMemory<NB, TB, LF, LC, NW, TW>,
    record_word_bits: 4,
    node_ports: {
        /// The root's link and padded box (x y z).
        pub root_first: Signal<Out, Bits<LF>>,
        pub root_count: Signal<Out, Bits<LC>>,
        pub root_min: [Signal<Out, Bits<32>>; 3],
        pub root_max: [Signal<Out, Bits<32>>; 3],
        /// Node read port: the node at `node_address`, one cycle later.
        pub node_address: Signal<In, Bits<NB>>,
        /// `min[2·axis + child]`, `max[2·axis + child]` (the box test's inputs).
        pub min: [Signal<Out, Bits<32>>; 6],
        pub max: [Signal<Out, Bits<32>>; 6],
        pub child_first: [Signal<Out, Bits<LF>>; 2],
        pub child_count: [Signal<Out, Bits<LC>>; 2],
    },
    node_registers: {
        root_first_reg: DFF<Bits<LF>>,
        root_count_reg: DFF<Bits<LC>>,
        root_box: DFF<Bits<192>>,
        /// The record being assembled: boxes shift in from the top, child 0's link.
        boxes: DFF<Bits<BOX_BITS>>,
        first0: DFF<Bits<LF>>,
        count0: DFF<Bits<LC>>,
    },
    format_constants: {},
    node_constants: {
        /// Bit offsets of the links in a node record, of the flag and index in a triangle record.
        at_first0: Constant<Bits<16>>,
        at_count0: Constant<Bits<16>>,
        at_first1: Constant<Bits<16>>,
        at_count1: Constant<Bits<16>>,
    },
    record_ends: {
        node_end: Constant<Bits<4>>,
    },
    format_errors: {},
    word_signals: {
        /// This word is a link's count (the root's, or a node child's).
        is_count: Signal<Local, Bit>,
    },
    node_signals: {
        /// first + count of the link whose count this is (33 bits: no wrap).
        leaf_end: Signal<Local, Bits<33>>,
    },
    read_signals: {},
    node_dffs: {
        root_first_reg,
        root_count_reg,
        root_box,
        boxes,
        first0,
        count0,
    },
    each_word: {
        self.is_count.next = false;
        self.leaf_end.next =
            bit_cast::<33, 32>(self.prev.q.val()) + bit_cast::<33, 32>(self.s_tdata.val());
    },
    node_record: {
        bit_cast::<NW, BOX_BITS>(self.boxes.q.val())
            | (bit_cast::<NW, LF>(self.first0.q.val()) << self.at_first0.val())
            | (bit_cast::<NW, LC>(self.count0.q.val()) << self.at_count0.val())
            | (bit_cast::<NW, LF>(bit_cast::<LF, 32>(self.prev.q.val())) << self.at_first1.val())
            | (bit_cast::<NW, LC>(bit_cast::<LC, 32>(self.s_tdata.val())) << self.at_count1.val())
    },
    header_counts: {
        // 16 + 16·N + 12·T words: the last is one less.
        self.last.d.next = self.header_end.val()
            + (self.n.q.val() << 4)
            + (self.s_tdata.val() << 3)
            + (self.s_tdata.val() << 2);
    },
    header_root: {
        if self.word.q.val() == 5 {
            self.is_count.next = true;
            self.root_first_reg.d.next = bit_cast::<LF, 32>(self.prev.q.val());
            self.root_count_reg.d.next = bit_cast::<LC, 32>(self.s_tdata.val());
        }
        if (self.word.q.val() >= 6) & (self.word.q.val() < 12) {
            self.root_box.d.next = (self.root_box.q.val() >> 32)
                | (bit_cast::<192, 32>(self.s_tdata.val()) << 160);
        }
    },
    header_tail: {
        if (self.word.q.val() >= 13) & self.s_tdata.val().any() {
            self.check.next = self.e_reserved.val();
        }
    },
    nodes: {
        self.k.d.next = self.k.q.val() + 1;
        if self.k.q.val() < 12 {
            self.boxes.d.next = (self.boxes.q.val() >> 32)
                | (bit_cast::<BOX_BITS, 32>(self.s_tdata.val()) << 352);
        }
        if self.k.q.val() == 13 {
            self.is_count.next = true;
            self.first0.d.next = bit_cast::<LF, 32>(self.prev.q.val());
            self.count0.d.next = bit_cast::<LC, 32>(self.s_tdata.val());
        }
        if self.k.q.val() == self.node_end.val() {
            self.is_count.next = true;
            self.node_ram.write_enable.next = true;
            self.k.d.next = 0.into();
            self.record.d.next = self.next_record.val();
            if self.next_record.val() == self.n.q.val() {
                self.record.d.next = 0.into();
                self.state.d.next = self.s_triangles.val();
            }
        }
    },
    links: {
        // A link (prev, this word): a node below N, else a leaf within T. The empty
        // scene's root (0, 0) with N = T = 0 is the one node link to no node.
        if self.is_count.val() {
            if !self.s_tdata.val().any() {
                if (self.prev.q.val() >= self.n.q.val())
                    & !(!self.prev.q.val().any()
                        & !self.n.q.val().any()
                        & !self.t.q.val().any())
                {
                    self.check.next = self.e_node_link.val();
                }
            } else if self.leaf_end.val() > bit_cast::<33, 32>(self.t.q.val()) {
                self.check.next = self.e_leaf_link.val();
            }
        }
    },
    root_outputs: {
        self.root_first.next = self.root_first_reg.q.val();
        self.root_count.next = self.root_count_reg.q.val();
        self.root_min[0].next = self.root_box.q.val().get_bits::<32>(0);
        self.root_min[1].next = self.root_box.q.val().get_bits::<32>(32);
        self.root_min[2].next = self.root_box.q.val().get_bits::<32>(64);
        self.root_max[0].next = self.root_box.q.val().get_bits::<32>(96);
        self.root_max[1].next = self.root_box.q.val().get_bits::<32>(128);
        self.root_max[2].next = self.root_box.q.val().get_bits::<32>(160);
    },
    node_fields: {
        self.min[0].next = self.node_read.val().get_bits::<32>(0);
        self.min[1].next = self.node_read.val().get_bits::<32>(32);
        self.min[2].next = self.node_read.val().get_bits::<32>(64);
        self.min[3].next = self.node_read.val().get_bits::<32>(96);
        self.min[4].next = self.node_read.val().get_bits::<32>(128);
        self.min[5].next = self.node_read.val().get_bits::<32>(160);
        self.max[0].next = self.node_read.val().get_bits::<32>(192);
        self.max[1].next = self.node_read.val().get_bits::<32>(224);
        self.max[2].next = self.node_read.val().get_bits::<32>(256);
        self.max[3].next = self.node_read.val().get_bits::<32>(288);
        self.max[4].next = self.node_read.val().get_bits::<32>(320);
        self.max[5].next = self.node_read.val().get_bits::<32>(352);
        self.child_first[0].next = bit_cast::<LF, NW>(self.node_read.val() >> self.at_first0.val());
        self.child_count[0].next = bit_cast::<LC, NW>(self.node_read.val() >> self.at_count0.val());
        self.child_first[1].next = bit_cast::<LF, NW>(self.node_read.val() >> self.at_first1.val());
        self.child_count[1].next = bit_cast::<LC, NW>(self.node_read.val() >> self.at_count1.val());
    },
}

/// The memory at `$nb` node and `$tb` triangle address bits, every width parameter
/// computed.
macro_rules! memory_sized {
    ($nb:literal, $tb:literal) => {
        SceneMemory<
            $nb,
            $tb,
            { link_first_bits($nb, $tb) },
            { link_count_bits($tb) },
            { node_record_bits($nb, $tb) },
            { triangle_record_bits() },
        >
    };
}

/// A memory for the small test images (16 nodes, 32 triangles).
pub type SceneMemory4x5 = memory_sized!(4, 5);
/// Glasses (425 nodes, 720 triangles) fits: 512 nodes, 1,024 triangles.
pub type SceneMemory9x10 = memory_sized!(9, 10);
/// 2,048 nodes, 4,096 triangles.
pub type SceneMemory11x12 = memory_sized!(11, 12);
/// Glass pen and Utah teapot (3,876 nodes, 6,322 triangles) fit: 4,096 nodes, 8,192 triangles.
pub type SceneMemory12x13 = memory_sized!(12, 13);

impl<
        const NB: usize,
        const TB: usize,
        const LF: usize,
        const LC: usize,
        const NW: usize,
        const TW: usize,
    > Default for SceneMemory<NB, TB, LF, LC, NW, TW>
{
    fn default() -> Self {
        Self::new(1)
    }
}

impl<
        const NB: usize,
        const TB: usize,
        const LF: usize,
        const LC: usize,
        const NW: usize,
        const TW: usize,
    > SceneMemory<NB, TB, LF, LC, NW, TW>
{
    /// A memory with `triangle_ports` triangle read ports (at least one). Panics when a width
    /// parameter is not the one derived from `NB` and `TB`.
    pub fn new(triangle_ports: usize) -> Self {
        assert!(
            triangle_ports >= 1,
            "a scene memory needs a triangle read port"
        );
        let (nodes, triangles) = capacity_for(NB, TB);
        // N and T are compared as 32-bit words.
        assert!(NB < 32 && TB < 32, "{NB}/{TB} address bits: at most 31");
        let want = [
            ("LF", LF, link_first_bits(NB, TB)),
            ("LC", LC, link_count_bits(TB)),
            ("NW", NW, node_record_bits(NB, TB)),
            ("TW", TW, triangle_record_bits()),
        ];
        for (name, got, want) in want {
            assert_eq!(
                got, want,
                "{name} for {NB} node and {TB} triangle address bits"
            );
        }
        let c16 = |x: usize| Constant::new((x as u64).into());
        let c4 = |x: usize| Constant::new((x as u64).into());
        scene_memory_new!(triangle_ports, nodes, triangles, {
            root_first: Default::default(),
            root_count: Default::default(),
            root_min: Default::default(),
            root_max: Default::default(),
            min: Default::default(),
            max: Default::default(),
            child_first: Default::default(),
            child_count: Default::default(),
            root_first_reg: Default::default(),
            root_count_reg: Default::default(),
            root_box: Default::default(),
            boxes: Default::default(),
            first0: Default::default(),
            count0: Default::default(),
            version: Constant::new(u64::from(VERSION).into()),
            at_first0: c16(BOX_BITS),
            at_count0: c16(BOX_BITS + LF),
            at_first1: c16(BOX_BITS + LF + LC),
            at_count1: c16(BOX_BITS + 2 * LF + LC),
            node_end: c4(NODE_WORDS - 1),
            triangle_end: c4(TRIANGLE_WORDS - 1),
            is_count: Default::default(),
        })
    }
}
