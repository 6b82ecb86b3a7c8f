//! The thesis scene formats (`.sod`, `.ood`, `.geo`, `objects.txt`): every field lands where it
//! belongs, every kind of bad input is reported with file, line and what was expected, no input
//! makes a parser panic, and the thesis' own scenes and templates load.

use std::fs;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{Vec2, Vec3};
use proptest::prelude::*;
use sw_renderer::scene::thesis::{load_dir, load_geo, parse_geo, parse_ood, parse_sod};
use sw_renderer::scene::{LightKind, Mat44, MaterialKind, Mesh, Scene, SceneError};

// ---------------------------------------------------------------------------------------------
// Helpers

/// Asserts `err` is a `Syntax` error in the file named `file` at `line`, where `token` was
/// found, whose message contains `phrase`.
#[track_caller]
fn assert_syntax(err: SceneError, file: &str, line: usize, token: &str, phrase: &str) {
    let shown = err.to_string();
    match err {
        SceneError::Syntax {
            path,
            line: l,
            token: t,
            what,
        } => {
            assert!(
                path.ends_with(file),
                "path {} is not {file}: {shown}",
                path.display()
            );
            assert_eq!(l, line, "line: {shown}");
            assert_eq!(t, token, "token: {shown}");
            assert!(what.contains(phrase), "message lacks {phrase:?}: {shown}");
            assert!(
                shown.contains(&format!("{file}:{line}:")),
                "display lacks file:line: {shown}"
            );
        }
        other => panic!("expected a syntax error, got {other:?}"),
    }
}

fn write_dir(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        fs::write(dir.path().join(name), text).unwrap();
    }
    dir
}

fn m(values: [f32; 16]) -> Mat44 {
    Mat44::from_row_major(values)
}

fn seq(start: f32) -> [f32; 16] {
    std::array::from_fn(|i| start + i as f32)
}

fn row(values: [f32; 16]) -> String {
    values.map(|v| v.to_string()).join(" ")
}

const GOOD_SOD: &str = "\
640 // width
480\t\t// height
45.5
0.1 0.2 0.3
1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16
0.0025
7
2
0
0.9 0.8 0.7
1.5
101 102 103 104 105 106 107 108 109 110 111 112 113 114 115 116
1
0.4 0.5 0.6
750
201 202 203 204 205 206 207 208 209 210 211 212 213 214 215 216
";

const GOOD_OOD: &str = "\
-1 -2 -3 -4 -5 -6 -7 -8 -9 -10 -11 -12 -13 -14 -15 -16
2
1.45
0.11 0.22 0.33
0.75
0.25
42
";

/// A triangle, a quad and a pentagon sharing vertices; normals and texture coordinates differ
/// at every face-vertex, so per-vertex and per-corner data cannot be confused.
const GOOD_GEO: &str = "\
3
3 4 5
0 1 2   2 1 3 4   4 3 5 6 0
0 0 0  1 0 0  0 1 0  1 1 0  0 2 0  2 2 0  3 3 3
0 0 1  0 0 2  0 0 3   1 0 0  2 0 0  3 0 0  4 0 0   5 0 0  6 0 0  7 0 0  8 0 0  9 0 0
0.1 0.1  0.2 0.2  0.3 0.3   1 1  2 2  3 3  4 4   5 5  6 6  7 7  8 8  9 9
";

// ---------------------------------------------------------------------------------------------
// Every field in its place

#[test]
fn sod_fields_land_in_place() {
    let (options, lights) = parse_sod(GOOD_SOD, Path::new("good.sod")).unwrap();
    assert_eq!((options.width, options.height), (640, 480));
    assert_eq!(options.fov_deg, 45.5);
    assert_eq!(options.background, Vec3::new(0.1, 0.2, 0.3));
    assert_eq!(options.camera_to_world, m(seq(1.0)));
    assert_eq!(
        options.camera_to_world.0[3],
        [13.0, 14.0, 15.0, 16.0],
        "row-major: translation row last"
    );
    assert_eq!(options.bias, 0.0025);
    assert_eq!(options.max_depth, 7);
    assert_eq!(lights.len(), 2);
    assert_eq!(lights[0].kind, LightKind::Distant);
    assert_eq!(lights[0].color, Vec3::new(0.9, 0.8, 0.7));
    assert_eq!(lights[0].intensity, 1.5);
    assert_eq!(lights[0].light_to_world, m(seq(101.0)));
    assert_eq!(lights[1].kind, LightKind::Point);
    assert_eq!(lights[1].color, Vec3::new(0.4, 0.5, 0.6));
    assert_eq!(lights[1].intensity, 750.0);
    assert_eq!(lights[1].light_to_world, m(seq(201.0)));
}

#[test]
fn sod_with_no_lights_is_accepted() {
    let text = "10 10 60 0 0 0 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 0.001 3 0 // no lights";
    let (_, lights) = parse_sod(text, Path::new("dark.sod")).unwrap();
    assert!(lights.is_empty());
}

#[test]
fn ood_fields_land_in_place() {
    let (object_to_world, material) = parse_ood(GOOD_OOD, Path::new("good.ood")).unwrap();
    assert_eq!(object_to_world, m(seq(1.0).map(|v| -v)));
    assert_eq!(material.kind, MaterialKind::ReflectionRefraction);
    assert_eq!(material.ior, 1.45);
    assert_eq!(material.albedo, Vec3::new(0.11, 0.22, 0.33));
    assert_eq!((material.kd, material.ks, material.n), (0.75, 0.25, 42.0));
}

#[test]
fn ood_material_types_map_to_kinds() {
    let kinds = [
        MaterialKind::Diffuse,
        MaterialKind::Reflection,
        MaterialKind::ReflectionRefraction,
        MaterialKind::Phong,
    ];
    for (code, kind) in kinds.into_iter().enumerate() {
        let text = GOOD_OOD.replacen("\n2\n", &format!("\n{code}\n"), 1);
        assert_eq!(
            parse_ood(&text, Path::new("k.ood")).unwrap().1.kind,
            kind,
            "type {code}"
        );
    }
}

#[test]
fn geo_fields_land_in_place_and_polygons_fan() {
    let mesh = parse_geo(GOOD_GEO, Path::new("good.geo")).unwrap();
    let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    assert_eq!(
        mesh.positions,
        [
            v(0., 0., 0.),
            v(1., 0., 0.),
            v(0., 1., 0.),
            v(1., 1., 0.),
            v(0., 2., 0.),
            v(2., 2., 0.),
            v(3., 3., 3.)
        ]
    );
    // Fans (k0, kj+1, kj+2): triangle 0 1 2; quad 2 1 3 4; pentagon 4 3 5 6 0.
    assert_eq!(
        mesh.triangles,
        [
            [0, 1, 2],
            [2, 1, 3],
            [2, 3, 4],
            [4, 3, 5],
            [4, 5, 6],
            [4, 6, 0]
        ]
    );
    let x = |k: f32| v(k, 0., 0.);
    assert_eq!(
        mesh.normals,
        [
            [v(0., 0., 1.), v(0., 0., 2.), v(0., 0., 3.)],
            [x(1.), x(2.), x(3.)],
            [x(1.), x(3.), x(4.)],
            [x(5.), x(6.), x(7.)],
            [x(5.), x(7.), x(8.)],
            [x(5.), x(8.), x(9.)],
        ]
    );
    let s = |k: f32| Vec2::new(k, k);
    assert_eq!(
        mesh.uvs,
        [
            [s(0.1), s(0.2), s(0.3)],
            [s(1.), s(2.), s(3.)],
            [s(1.), s(3.), s(4.)],
            [s(5.), s(6.), s(7.)],
            [s(5.), s(7.), s(8.)],
            [s(5.), s(8.), s(9.)],
        ]
    );
}

/// An independent description of the `.geo` layout: random polygons written out, read back.
fn polygon_meshes() -> impl Strategy<Value = Vec<Vec<u32>>> {
    prop::collection::vec(prop::collection::vec(0u32..12, 3..7), 1..6)
}

proptest! {
    #[test]
    fn geo_round_trips_random_polygons(faces in polygon_meshes()) {
        let vertices = faces.iter().flatten().max().unwrap() + 1;
        let corners: usize = faces.iter().map(Vec::len).sum();
        let position = |i: u32| [i as f32, 0.5 * i as f32, -(i as f32)];
        let normal = |c: usize| [c as f32, 1.0, 2.0];
        let uv = |c: usize| [c as f32 * 0.25, 3.0];
        let mut text = format!("{}\n", faces.len());
        text += &faces.iter().map(|f| f.len().to_string()).collect::<Vec<_>>().join(" ");
        text += "\n";
        text += &faces.iter().flatten().map(u32::to_string).collect::<Vec<_>>().join(" ");
        text += "\n";
        for i in 0..vertices { text += &format!("{:?} ", position(i)).replace([',', '[', ']'], ""); }
        text += "\n";
        for c in 0..corners { text += &format!("{:?} ", normal(c)).replace([',', '[', ']'], ""); }
        text += "\n";
        for c in 0..corners { text += &format!("{:?} ", uv(c)).replace([',', '[', ']'], ""); }

        let mesh = parse_geo(&text, Path::new("random.geo")).unwrap();
        prop_assert_eq!(mesh.positions.len(), vertices as usize);
        for (i, p) in mesh.positions.iter().enumerate() {
            prop_assert_eq!(p.to_array(), position(i as u32));
        }
        let expected_triangles: usize = faces.iter().map(|f| f.len() - 2).sum();
        prop_assert_eq!(mesh.triangles.len(), expected_triangles);
        prop_assert_eq!(mesh.normals.len(), expected_triangles);
        prop_assert_eq!(mesh.uvs.len(), expected_triangles);
        let (mut t, mut first) = (0, 0);
        for face in &faces {
            for j in 1..face.len() - 1 {
                let corner = [first, first + j, first + j + 1];
                prop_assert_eq!(mesh.triangles[t], corner.map(|c| face[c - first]));
                prop_assert_eq!(mesh.normals[t].map(|n| n.to_array()), corner.map(normal));
                prop_assert_eq!(mesh.uvs[t].map(|uv| uv.to_array()), corner.map(uv));
                t += 1;
            }
            first += face.len();
        }
    }

    #[test]
    fn sod_round_trips_random_values(
        size in (1u32..100_000, 1u32..100_000),
        fov in 0.001f32..179.9,
        background in prop::array::uniform3(-1e6f32..1e6),
        camera in prop::array::uniform16(-1e6f32..1e6),
        bias in -1.0f32..1.0,
        depth in 0u32..1000,
        lights in prop::collection::vec(
            (0u32..2, prop::array::uniform3(0f32..10.0), 0f32..1e4, prop::array::uniform16(-1e3f32..1e3)),
            0..4,
        ),
    ) {
        let mut text = format!(
            "{} {}\n{fov}\n{} {} {}\n{}\n{bias}\n{depth}\n{}\n",
            size.0, size.1, background[0], background[1], background[2], row(camera), lights.len()
        );
        for (kind, color, intensity, matrix) in &lights {
            text += &format!("{kind} {} {} {} {intensity} {} // light\n", color[0], color[1], color[2], row(*matrix));
        }
        let (options, parsed) = parse_sod(&text, Path::new("random.sod")).unwrap();
        prop_assert_eq!((options.width, options.height), size);
        prop_assert_eq!(options.fov_deg, fov);
        prop_assert_eq!(options.background.to_array(), background);
        prop_assert_eq!(options.camera_to_world, m(camera));
        prop_assert_eq!((options.bias, options.max_depth), (bias, depth));
        prop_assert_eq!(parsed.len(), lights.len());
        for (light, (kind, color, intensity, matrix)) in parsed.iter().zip(&lights) {
            let expected_kind = if *kind == 0 { LightKind::Distant } else { LightKind::Point };
            prop_assert_eq!(light.kind, expected_kind);
            prop_assert_eq!(light.color.to_array(), *color);
            prop_assert_eq!(light.intensity, *intensity);
            prop_assert_eq!(light.light_to_world, m(*matrix));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Bad input: file, line, found token and what was expected

#[test]
fn truncated_files_say_what_was_expected_at_end_of_file() {
    let err = parse_sod("640\n480\n45\n", Path::new("cut.sod")).unwrap_err();
    assert_syntax(
        err,
        "cut.sod",
        3,
        "end of file",
        "component 1 of 3 of the background colour",
    );

    let cut = GOOD_OOD.lines().take(3).collect::<Vec<_>>().join("\n");
    let err = parse_ood(&cut, Path::new("cut.ood")).unwrap_err();
    assert_syntax(err, "cut.ood", 3, "end of file", "albedo");

    // One texture coordinate pair short.
    let cut = GOOD_GEO.trim_end().trim_end_matches("9 9").to_string();
    let err = parse_geo(&cut, Path::new("cut.geo")).unwrap_err();
    assert_syntax(
        err,
        "cut.geo",
        6,
        "end of file",
        "texture coordinate 12 of 12",
    );

    let err = parse_geo("", Path::new("empty.geo")).unwrap_err();
    assert_syntax(err, "empty.geo", 1, "end of file", "number of faces");
}

#[test]
fn fewer_lights_than_announced_is_reported() {
    let text = GOOD_SOD.replacen("\n2\n", "\n3\n", 1);
    let err = parse_sod(&text, Path::new("lights.sod")).unwrap_err();
    assert_syntax(err, "lights.sod", 16, "end of file", "type of light 3 of 3");
}

#[test]
fn non_numbers_nan_and_infinity_are_rejected() {
    let err = parse_sod(&GOOD_SOD.replacen("640", "six40", 1), Path::new("a.sod")).unwrap_err();
    assert_syntax(err, "a.sod", 1, "six40", "image width");

    let err = parse_sod(&GOOD_SOD.replacen("45.5", "NaN", 1), Path::new("a.sod")).unwrap_err();
    assert_syntax(
        err,
        "a.sod",
        3,
        "NaN",
        "the fov in degrees (a finite number",
    );

    let err = parse_sod(&GOOD_SOD.replacen("0.0025", "inf", 1), Path::new("a.sod")).unwrap_err();
    assert_syntax(err, "a.sod", 6, "inf", "shadow bias (a finite number)");

    let err = parse_ood(&GOOD_OOD.replacen("0.22", "nan", 1), Path::new("b.ood")).unwrap_err();
    assert_syntax(
        err,
        "b.ood",
        4,
        "nan",
        "component 2 of 3 of the albedo (a finite number)",
    );

    // Overflows f32 to infinity.
    let err = parse_ood(&GOOD_OOD.replacen("-7", "1e39", 1), Path::new("b.ood")).unwrap_err();
    assert_syntax(
        err,
        "b.ood",
        1,
        "1e39",
        "element 7 of 16 of the object-to-world matrix",
    );

    let err = parse_geo(
        &GOOD_GEO.replacen("3 3 3", "3 -inf 3", 1),
        Path::new("c.geo"),
    )
    .unwrap_err();
    assert_syntax(
        err,
        "c.geo",
        4,
        "-inf",
        "component 2 of 3 of the position of vertex 7 of 7",
    );

    let err = parse_geo(
        &GOOD_GEO.replacen("0.3 0.3", "0.3 x", 1),
        Path::new("c.geo"),
    )
    .unwrap_err();
    assert_syntax(err, "c.geo", 6, "x", "texture coordinate 3 of 12");
}

#[test]
fn counts_and_sizes_must_be_positive_whole_numbers() {
    let err = parse_sod(&GOOD_SOD.replacen("640", "-640", 1), Path::new("s.sod")).unwrap_err();
    assert_syntax(err, "s.sod", 1, "-640", "image width (a whole number ≥ 1)");
    let err = parse_sod(&GOOD_SOD.replacen("480", "0", 1), Path::new("s.sod")).unwrap_err();
    assert_syntax(err, "s.sod", 2, "0", "image height");
    let err = parse_sod(&GOOD_SOD.replacen("640", "640.0", 1), Path::new("s.sod")).unwrap_err();
    assert_syntax(err, "s.sod", 1, "640.0", "image width");
    let err = parse_sod(&GOOD_SOD.replacen("\n7\n", "\n+7\n", 1), Path::new("s.sod")).unwrap_err();
    assert_syntax(err, "s.sod", 7, "+7", "max depth");
    let err = parse_sod(
        &GOOD_SOD.replacen("\n2\n", "\n2.5\n", 1),
        Path::new("s.sod"),
    )
    .unwrap_err();
    assert_syntax(err, "s.sod", 8, "2.5", "number of lights");
    let err = parse_sod(&GOOD_SOD.replacen("45.5", "180", 1), Path::new("s.sod")).unwrap_err();
    assert_syntax(err, "s.sod", 3, "180", "between 0 and 180");

    let err = parse_geo(&GOOD_GEO.replacen("3\n", "3.0\n", 1), Path::new("g.geo")).unwrap_err();
    assert_syntax(err, "g.geo", 1, "3.0", "number of faces");
    let err = parse_geo(&GOOD_GEO.replacen("3\n", "0\n", 1), Path::new("g.geo")).unwrap_err();
    assert_syntax(err, "g.geo", 1, "0", "number of faces (a whole number ≥ 1)");
    let err = parse_geo(
        &GOOD_GEO.replacen("3 4 5", "3 4.0 5", 1),
        Path::new("g.geo"),
    )
    .unwrap_err();
    assert_syntax(
        err,
        "g.geo",
        2,
        "4.0",
        "face-vertex count ≥ 3 for face 2 of 3",
    );
    let err = parse_geo(
        &GOOD_GEO.replacen("0 1 2 ", "0 -1 2 ", 1),
        Path::new("g.geo"),
    )
    .unwrap_err();
    assert_syntax(err, "g.geo", 3, "-1", "vertex index 2 of 12");
}

#[test]
fn a_face_with_two_vertices_is_rejected() {
    let text = "2\n3\n2\n0 1 2 0 1\n";
    let err = parse_geo(text, Path::new("two.geo")).unwrap_err();
    assert_syntax(
        err,
        "two.geo",
        3,
        "2",
        "face-vertex count ≥ 3 for face 2 of 2",
    );
}

#[test]
fn a_vertex_index_beyond_the_positions_is_out_of_range() {
    // Index 17 on line 3, but only 3 positions (9 numbers) before the 3 normals and 3 uvs.
    let text = "1\n3\n0 1\n17\n0 0 0 1 0 0 0 1 0\n0 0 1 0 0 1 0 0 1\n0 0 1 0 0 1\n";
    let err = parse_geo(text, Path::new("range.geo")).unwrap_err();
    assert_syntax(
        err,
        "range.geo",
        4,
        "17",
        "vertex index 17 out of range: the file has 3 vertices",
    );
}

#[test]
fn unknown_material_and_light_types_are_rejected() {
    let err = parse_ood(&GOOD_OOD.replacen("\n2\n", "\n4\n", 1), Path::new("t.ood")).unwrap_err();
    assert_syntax(
        err,
        "t.ood",
        2,
        "4",
        "material type (0 diffuse, 1 reflection",
    );
    let err = parse_sod(
        &GOOD_SOD.replacen("\n1\n0.4", "\n2\n0.4", 1),
        Path::new("t.sod"),
    )
    .unwrap_err();
    assert_syntax(
        err,
        "t.sod",
        13,
        "2",
        "type of light 2 of 2 (0 distant, 1 point)",
    );
}

#[test]
fn trailing_garbage_is_rejected_but_trailing_comments_are_not() {
    let err = parse_ood(&format!("{GOOD_OOD}\n 7 // extra"), Path::new("x.ood")).unwrap_err();
    assert_syntax(err, "x.ood", 9, "7", "the end of the file after n");
    let err = parse_sod(&format!("{GOOD_SOD}oops"), Path::new("x.sod")).unwrap_err();
    assert_syntax(
        err,
        "x.sod",
        17,
        "oops",
        "end of the file after the 2 light(s)",
    );
    let err = parse_geo(&format!("{GOOD_GEO}1"), Path::new("x.geo")).unwrap_err();
    assert_syntax(
        err,
        "x.geo",
        7,
        "1",
        "end of the file after the texture coordinates",
    );

    parse_ood(
        &format!("{GOOD_OOD}\n  \t\n// the end\n\n"),
        Path::new("x.ood"),
    )
    .unwrap();
    parse_geo(&format!("{GOOD_GEO}   // done"), Path::new("x.geo")).unwrap();
}

// ---------------------------------------------------------------------------------------------
// Scene directories

const PLANE_GEO: &str =
    "1\n4\n0 1 3 2\n-1 0 1 1 0 1 -1 0 -1 1 0 -1\n0 1 0 0 1 0 0 1 0 0 1 0\n0 0 1 0 0 1 1 1\n";
const LIGHTLESS_SOD: &str = "8 6 60 0 0 0 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 0.001 3 0";

#[test]
fn a_scene_directory_loads_in_order_and_shares_geometry() {
    let red = GOOD_OOD.replacen("\n2\n", "\n0\n", 1);
    let dir = write_dir(&[
        ("s.sod", GOOD_SOD),
        ("objects.txt", "# comment\n\nplane.geo red.ood\n  # indented comment\ngood.geo glass.ood\nplane.geo glass.ood\n"),
        ("plane.geo", PLANE_GEO),
        ("good.geo", GOOD_GEO),
        ("red.ood", &red),
        ("glass.ood", GOOD_OOD),
    ]);
    let scene = load_dir(dir.path()).unwrap();
    assert_eq!(
        scene.name,
        dir.path().file_name().unwrap().to_string_lossy()
    );
    assert_eq!(scene.lights.len(), 2);
    assert_eq!(scene.options.width, 640);
    let names: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "plane.geo+red.ood",
            "good.geo+glass.ood",
            "plane.geo+glass.ood"
        ]
    );
    assert!(
        Arc::ptr_eq(&scene.objects[0].mesh, &scene.objects[2].mesh),
        "plane.geo parsed once"
    );
    assert!(!Arc::ptr_eq(&scene.objects[0].mesh, &scene.objects[1].mesh));
    assert_eq!(
        *scene.objects[1].mesh,
        parse_geo(GOOD_GEO, Path::new("good.geo")).unwrap()
    );
    assert_eq!(scene.objects[0].mesh.triangles, [[0, 1, 3], [0, 3, 2]]);
    assert_eq!(scene.objects[0].material.kind, MaterialKind::Diffuse);
    assert_eq!(
        scene.objects[1].material.kind,
        MaterialKind::ReflectionRefraction
    );
    assert_eq!(scene.objects[2].object_to_world, m(seq(1.0).map(|v| -v)));
    assert_eq!(scene.triangle_count(), 2 + 6 + 2);
    // The generic entry point recognises a directory.
    assert_eq!(Scene::load(dir.path().to_str().unwrap()).unwrap(), scene);
}

#[track_caller]
fn assert_io_names(err: SceneError, missing: &Path) {
    let shown = err.to_string();
    match err {
        SceneError::Io { path, .. } => assert_eq!(path, missing, "{shown}"),
        other => panic!(
            "expected an I/O error naming {}, got {other:?}",
            missing.display()
        ),
    }
    assert!(shown.contains(&missing.display().to_string()), "{shown}");
}

#[test]
fn missing_files_are_named() {
    let dir = write_dir(&[
        ("s.sod", LIGHTLESS_SOD),
        ("objects.txt", "plane.geo p.ood\n"),
        ("plane.geo", PLANE_GEO),
    ]);
    assert_io_names(load_dir(dir.path()).unwrap_err(), &dir.path().join("p.ood"));

    fs::write(dir.path().join("objects.txt"), "nowhere.geo p.ood\n").unwrap();
    assert_io_names(
        load_dir(dir.path()).unwrap_err(),
        &dir.path().join("nowhere.geo"),
    );

    fs::remove_file(dir.path().join("objects.txt")).unwrap();
    assert_io_names(
        load_dir(dir.path()).unwrap_err(),
        &dir.path().join("objects.txt"),
    );

    assert_io_names(
        load_geo(&dir.path().join("none.geo")).unwrap_err(),
        &dir.path().join("none.geo"),
    );
}

#[test]
fn the_sod_must_be_exactly_one() {
    let dir = write_dir(&[
        ("objects.txt", "plane.geo p.ood\n"),
        ("plane.geo", PLANE_GEO),
        ("p.ood", GOOD_OOD),
    ]);
    let shown = load_dir(dir.path()).unwrap_err().to_string();
    assert!(shown.contains("no .sod"), "{shown}");

    fs::write(dir.path().join("a.sod"), LIGHTLESS_SOD).unwrap();
    load_dir(dir.path()).unwrap();

    fs::write(dir.path().join("b.sod"), LIGHTLESS_SOD).unwrap();
    let err = load_dir(dir.path()).unwrap_err();
    let shown = err.to_string();
    assert!(
        matches!(err, SceneError::Invalid { ref path, .. } if path == dir.path()),
        "{shown}"
    );
    assert!(
        shown.contains("2 .sod") && shown.contains("a.sod, b.sod"),
        "{shown}"
    );
}

#[test]
fn bad_object_list_lines_are_reported() {
    let dir = write_dir(&[
        ("s.sod", LIGHTLESS_SOD),
        (
            "objects.txt",
            "# objects\nplane.geo p.ood\nplane.geo p.ood extra.ood\n",
        ),
        ("plane.geo", PLANE_GEO),
        ("p.ood", GOOD_OOD),
    ]);
    let err = load_dir(dir.path()).unwrap_err();
    assert_syntax(
        err,
        "objects.txt",
        3,
        "plane.geo p.ood extra.ood",
        "pair (2 file names, found 3)",
    );

    fs::write(dir.path().join("objects.txt"), "plane.geo\n").unwrap();
    assert_syntax(
        load_dir(dir.path()).unwrap_err(),
        "objects.txt",
        1,
        "plane.geo",
        "found 1",
    );

    fs::write(dir.path().join("objects.txt"), "# only comments\n\n").unwrap();
    let shown = load_dir(dir.path()).unwrap_err().to_string();
    assert!(
        shown.contains("objects.txt") && shown.contains("lists no objects"),
        "{shown}"
    );
}

#[test]
fn errors_inside_listed_files_name_those_files() {
    let dir = write_dir(&[
        ("s.sod", LIGHTLESS_SOD),
        ("objects.txt", "plane.geo p.ood\n"),
        ("plane.geo", PLANE_GEO),
        ("p.ood", &GOOD_OOD.replacen("0.75", "heavy", 1)),
    ]);
    assert_syntax(load_dir(dir.path()).unwrap_err(), "p.ood", 5, "heavy", "Kd");
}

// ---------------------------------------------------------------------------------------------
// No input makes a parser panic

type Parser = fn(&str) -> Result<(), SceneError>;

const PARSERS: [(&str, &str, Parser); 3] = [
    ("fuzz.sod", GOOD_SOD, |t| {
        parse_sod(t, Path::new("fuzz.sod")).map(drop)
    }),
    ("fuzz.ood", GOOD_OOD, |t| {
        parse_ood(t, Path::new("fuzz.ood")).map(drop)
    }),
    ("fuzz.geo", GOOD_GEO, |t| {
        parse_geo(t, Path::new("fuzz.geo")).map(drop)
    }),
];

/// Runs every parser on `text`; a panic fails the test, an error must name the file.
fn parse_all(text: &str) -> Result<(), TestCaseError> {
    for (file, _, parse) in PARSERS {
        if let Err(err) = parse(text) {
            let shown = err.to_string();
            prop_assert!(
                shown.starts_with(file),
                "error does not name {}: {}",
                file,
                shown
            );
        }
    }
    Ok(())
}

/// Tokens that stress the parsers: huge counts, signs, non-finite values, comment markers.
fn nasty_token() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("4294967295".to_string()),
        Just("4294967296".to_string()),
        Just("99999999999999999999999".to_string()),
        Just("1000000000".to_string()),
        Just("-1".to_string()),
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("1e39".to_string()),
        Just("0".to_string()),
        Just("2".to_string()),
        Just("//".to_string()),
        Just("\n".to_string()),
        Just("é".to_string()),
        "[-+0-9.eE]{1,6}",
    ]
}

/// A valid file with random edits: deleted stretches, inserted or replacing tokens.
fn mutated(base: &'static str) -> impl Strategy<Value = String> {
    let edit = (
        any::<prop::sample::Index>(),
        0usize..8,
        prop::option::of(nasty_token()),
    );
    prop::collection::vec(edit, 1..6).prop_map(move |edits| {
        let mut text: Vec<char> = base.chars().collect();
        for (at, delete, insert) in edits {
            let start = at.index(text.len() + 1);
            let end = (start + delete).min(text.len());
            let replacement: Vec<char> = insert
                .map(|s| format!(" {s} "))
                .unwrap_or_default()
                .chars()
                .collect();
            text.splice(start..end, replacement);
        }
        text.into_iter().collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn parsers_never_panic_on_random_text(text in "[-+0-9 .eEnaif/x\\n\\t]{0,300}") {
        parse_all(&text)?;
    }

    #[test]
    fn parsers_never_panic_on_token_soup(tokens in prop::collection::vec(nasty_token(), 0..60)) {
        parse_all(&tokens.join(" "))?;
    }

    #[test]
    fn parsers_never_panic_on_mutated_files(
        sod in mutated(GOOD_SOD),
        ood in mutated(GOOD_OOD),
        geo in mutated(GOOD_GEO),
    ) {
        for text in [sod, ood, geo] {
            parse_all(&text)?;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The thesis' own scenes and templates

/// The thesis scenes, or None after a `SKIPPED thesis_format::<test>` line.
fn thesis_dir(test: &str) -> Option<PathBuf> {
    sw_renderer::thesis_scenes::for_test(&format!("thesis_format::{test}"))
}

/// Σ(n − 2) over the face-vertex counts, read straight from the file's first tokens.
fn fan_triangles_in(geo: &Path) -> usize {
    let text = fs::read_to_string(geo).unwrap();
    let mut tokens = text.split_whitespace().map(|t| t.parse::<usize>().unwrap());
    let faces = tokens.next().unwrap();
    tokens.take(faces).map(|n| n - 2).sum()
}

#[test]
fn the_thesis_scenes_load() {
    let Some(root) = thesis_dir("the_thesis_scenes_load") else {
        return;
    };
    let mut dirs: Vec<PathBuf> = fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir() && !p.ends_with("Default_options_files"))
        .collect();
    dirs.sort();
    assert_eq!(dirs.len(), 7, "the thesis has 7 scenes: {dirs:?}");

    for dir in dirs {
        let scene = load_dir(&dir).unwrap_or_else(|e| panic!("{e}"));
        let listed: Vec<(String, String)> = fs::read_to_string(dir.join("objects.txt"))
            .unwrap()
            .lines()
            .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
            .map(|l| {
                let mut names = l.split_whitespace().map(str::to_string);
                (names.next().unwrap(), names.next().unwrap())
            })
            .collect();
        assert_eq!(scene.objects.len(), listed.len(), "{}", scene.name);
        assert_eq!(scene.name, dir.file_name().unwrap().to_string_lossy());
        assert_eq!(
            (scene.options.width, scene.options.height),
            (1920, 1080),
            "{}",
            scene.name
        );
        assert!(!scene.lights.is_empty(), "{}", scene.name);

        println!(
            "{}: {} objects, {} triangles, {} lights",
            scene.name,
            scene.objects.len(),
            scene.triangle_count(),
            scene.lights.len()
        );
        for (object, (geo, ood)) in scene.objects.iter().zip(&listed) {
            assert_eq!(object.name, format!("{geo}+{ood}"));
            let mesh: &Mesh = &object.mesh;
            println!(
                "  {:28} {:6} triangles {:6} vertices",
                object.name,
                mesh.triangles.len(),
                mesh.positions.len()
            );
            assert_eq!(
                mesh.triangles.len(),
                fan_triangles_in(&dir.join(geo)),
                "{}",
                object.name
            );
            assert!(!mesh.triangles.is_empty());
            assert_eq!(mesh.normals.len(), mesh.triangles.len());
            assert_eq!(mesh.uvs.len(), mesh.triangles.len());
            let vertices = mesh.positions.len() as u32;
            assert!(
                mesh.triangles.iter().flatten().all(|&i| i < vertices),
                "{}",
                object.name
            );
            assert!(
                mesh.triangles.iter().flatten().any(|&i| i == vertices - 1),
                "vertex count = max index + 1"
            );
            for corner in mesh.normals.iter().flatten() {
                assert!(
                    (corner.length() - 1.0).abs() < 0.05,
                    "{}: normal {corner} not unit",
                    object.name
                );
            }
        }
        for (i, a) in listed.iter().enumerate() {
            for (j, b) in listed.iter().enumerate() {
                let shared = Arc::ptr_eq(&scene.objects[i].mesh, &scene.objects[j].mesh);
                assert_eq!(shared, a.0 == b.0, "{}: objects {i} and {j}", scene.name);
            }
        }
    }
}

#[test]
fn the_simple_plane_scene_has_the_expected_values() {
    let Some(root) = thesis_dir("the_simple_plane_scene_has_the_expected_values") else {
        return;
    };
    let scene = load_dir(&root.join("Simple_plane_scene")).unwrap();
    assert_eq!(scene.options.fov_deg, 36.87);
    assert_eq!(scene.options.camera_to_world.0[3], [0.0, 20.0, 75.0, 1.0]);
    assert_eq!((scene.options.bias, scene.options.max_depth), (0.0001, 4));
    assert_eq!(scene.lights[0].kind, LightKind::Distant);
    assert_eq!(scene.lights[0].color, Vec3::new(0.6, 0.6, 1.0));
    let plane = &scene.objects[0].mesh;
    assert_eq!(plane.triangles, [[0, 1, 3], [0, 3, 2]]);
    assert_eq!(
        plane.positions[0],
        Vec3::new(-10.0, "-2.220446049e-15".parse().unwrap(), 10.0)
    );
    assert_eq!(
        plane.uvs[1],
        [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0)
        ]
    );
}

/// The templates are annotated documents: each line holds its values, a label and a `//`
/// comment; matrices are placeholders ("Camera 2 world no default") and the material type is
/// the word `kDiffuse`. Filling them in — matrices by the identity, `kDiffuse` by its code 0
/// (as the template's comment says), labels dropped — must give parseable files whose values
/// are the template's, with tabs and `//` comments left in place.
fn fill_in_template(text: &str) -> String {
    let identity = row(Mat44::IDENTITY.0.concat().try_into().unwrap());
    let mut filled = String::new();
    for line in text.lines() {
        let (code, comment) = line.split_once("//").map_or((line, ""), |(c, m)| (c, m));
        let values = if code.contains("2 world no default") {
            identity.clone()
        } else {
            code.split_whitespace()
                .map(|w| if w == "kDiffuse" { "0" } else { w })
                .filter(|w| w.parse::<f32>().is_ok())
                .collect::<Vec<_>>()
                .join(" ")
        };
        filled += &format!("{values}\t\t// {comment}\n");
    }
    filled
}

#[test]
fn the_default_option_templates_parse_once_filled_in() {
    let Some(root) = thesis_dir("the_default_option_templates_parse_once_filled_in") else {
        return;
    };
    let templates = root.join("Default_options_files");
    assert!(
        templates.is_dir(),
        "{} is not a directory",
        templates.display()
    );

    let path = templates.join("scene_default.sod");
    let raw = fs::read_to_string(&path).unwrap();
    assert_syntax(
        parse_sod(&raw, &path).unwrap_err(),
        "scene_default.sod",
        1,
        "width",
        "image height",
    );
    let (options, lights) = parse_sod(&fill_in_template(&raw), &path).unwrap();
    assert_eq!(
        (options.width, options.height, options.fov_deg),
        (1920, 1080, 90.0)
    );
    assert_eq!(options.background, Vec3::new(0.235294, 0.67451, 0.843137));
    assert_eq!(options.camera_to_world, Mat44::IDENTITY);
    assert_eq!((options.bias, options.max_depth), (0.0001, 4));
    assert_eq!(lights.len(), 1);
    assert_eq!(lights[0].kind, LightKind::Distant);
    assert_eq!((lights[0].color, lights[0].intensity), (Vec3::ONE, 1.0));

    let path = templates.join("object_default.ood");
    let raw = fs::read_to_string(&path).unwrap();
    assert_syntax(
        parse_ood(&raw, &path).unwrap_err(),
        "object_default.ood",
        1,
        "Object",
        "element 1 of 16",
    );
    let (object_to_world, material) = parse_ood(&fill_in_template(&raw), &path).unwrap();
    assert_eq!(object_to_world, Mat44::IDENTITY);
    assert_eq!(material.kind, MaterialKind::Diffuse);
    assert_eq!((material.ior, material.albedo), (1.0, Vec3::splat(0.18)));
    assert_eq!((material.kd, material.ks, material.n), (0.8, 0.2, 10.0));

    // The geometry template is prose followed by a cube example.
    let path = templates.join("Geometry_file_template.geo");
    let raw = fs::read_to_string(&path).unwrap();
    assert_syntax(
        parse_geo(&raw, &path).unwrap_err(),
        "Geometry_file_template.geo",
        1,
        "The",
        "number of faces",
    );
    let (_, cube_text) = raw.split_once("Cube example").unwrap();
    let cube = parse_geo(cube_text, &path).unwrap();
    assert_eq!(cube.positions.len(), 8);
    assert_eq!(cube.triangles.len(), 12);
    assert_eq!(
        &cube.triangles[..4],
        [[0, 1, 2], [0, 2, 3], [0, 4, 5], [0, 5, 1]]
    );
    assert_eq!(cube.normals[0], [Vec3::Z; 3]);
    assert_eq!(cube.normals[2], [Vec3::Y; 3]);
    assert_eq!(
        cube.uvs[0],
        [
            Vec2::new(0.375, 0.625),
            Vec2::new(0.625, 0.375),
            Vec2::new(0.375, 0.625)
        ]
    );
}
