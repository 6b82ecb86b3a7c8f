//! `hdl::traversal::scene_memory_driver`.

use hdl::traversal::scene_memory::LoadError;
use hdl::traversal::scene_memory_driver::*;

#[test]
fn words_are_placed_in_header_nodes_and_triangles() {
    assert_eq!(word_place(2, 3), "header word 2");
    assert_eq!(
        word_place(16 + 16 + 13, 3),
        "node 1 word 13: link count of child 0"
    );
    assert_eq!(
        word_place(16 + 15, 3),
        "node 0 word 15: link count of child 1"
    );
    assert_eq!(
        word_place(16 + 48 + 12 + 9, 3),
        "triangle record 1 word 9: global index"
    );
}

#[test]
fn codes_round_trip_and_unknown_codes_are_errors() {
    for e in LoadError::ALL {
        assert_eq!(LoadError::from_code(e.code()), Some(e));
    }
    assert_eq!(LoadError::from_code(0), None);
    let status = LoadStatus {
        error_code: 15,
        error_word: 4,
        ..Default::default()
    };
    let config = MemoryConfig {
        node_bits: 4,
        triangle_bits: 5,
    };
    assert_eq!(
        status_result(&status, &[], config),
        Err(SceneMemoryError::UnknownCode { code: 15, word: 4 })
    );
    let hung = LoadStatus {
        loading: true,
        ..Default::default()
    };
    let err = status_result(&hung, &[0; 20], config).unwrap_err();
    assert!(err.to_string().contains("20 words"), "{err}");
}
