//! Malformed scene files: TOML scenes and thesis scene directories name the file, the line
//! and what was expected.

use std::path::{Path, PathBuf};

use image::Rgb;

use crate::common::*;

fn simple_plane_toml() -> String {
    std::fs::read_to_string(Path::new(REPO).join("scenes/simple_plane.toml")).unwrap()
}

/// Writes `text` with the line starting `old` replaced by `new` to `dir/name`; returns the
/// path and the 1-based number of that line.
fn with_line(dir: &Path, name: &str, text: &str, old: &str, new: &str) -> (PathBuf, usize) {
    let mut number = None;
    let lines: Vec<String> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if number.is_none() && l.trim_start().starts_with(old) {
                number = Some(i + 1);
                new.to_string()
            } else {
                l.to_string()
            }
        })
        .collect();
    let number = number.unwrap_or_else(|| panic!("no line starting {old:?}"));
    let path = dir.join(name);
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    (path, number)
}

#[test]
fn malformed_toml_scenes_name_the_file_the_line_and_what_was_expected() {
    let dir = tmp();
    let out_png = at(&dir, "x.png");
    let base = simple_plane_toml();
    // The unbroken copy renders: the failures below are the edits'.
    let good = dir.path().join("good.toml");
    std::fs::write(&good, &base).unwrap();
    render(s(&good), 8, 4, &out_png).ok();
    std::fs::remove_file(&out_png).unwrap();

    let cases = [
        (
            "fov.toml",
            "fov =",
            "fov = 200",
            vec!["`200`", "fov", "between 0 and 180"],
        ),
        (
            "key.toml",
            "color =",
            "colour = [0.6, 0.6, 1]",
            vec!["unknown field `colour`", "`color`"],
        ),
        (
            "kind.toml",
            "kind = \"distant\"",
            "kind = \"spot\"",
            vec!["spot", "distant", "point"],
        ),
        ("nan.toml", "intensity =", "intensity = nan", vec!["finite"]),
    ];
    for (name, old, new, needles) in cases {
        let (path, line) = with_line(dir.path(), name, &base, old, new);
        let at = format!("{name}:{line}");
        let mut all = vec![at.as_str()];
        all.extend(needles);
        render(s(&path), 8, 4, &out_png).fails(1, &all);
    }
    // A TOML syntax error: the file and a line number at or just after the broken line.
    let (path, line) = with_line(
        dir.path(),
        "syntax.toml",
        &base,
        "height =",
        "height = [360",
    );
    let stderr = rtfpga(&["render", "--scene", s(&path)])
        .out(&out_png)
        .fails(1, &["syntax.toml:"]);
    assert!(
        stderr.contains(&format!("syntax.toml:{line}:"))
            || stderr.contains(&format!("syntax.toml:{}:", line + 1)),
        "{stderr}"
    );
    assert!(!out_png.exists());
}

const SOD: &str = "\
// width height fov
32 18 40
0.2 0.3 0.4
1 0 0 0
0 1 0 0
0 0 1 0
0 5 20 1
0.0001 4
1
0 1 1 1 1
1 0 0 0
0 0 -1 0
0 1 0 0
0 0 0 1
";

const OOD: &str = "\
1 0 0 0
0 1 0 0
0 0 1 0
0 0 0 1
0 1 0.18 0.18 0.18 0.8 0.2 10
";

const GEO: &str = "\
1
4
0 1 2 3
-10 0 10  10 0 10  10 0 -10  -10 0 -10
0 1 0  0 1 0  0 1 0  0 1 0
0 0  1 0  1 1  0 1
";

/// A thesis scene directory with `files` replaced/added, under `parent/name`.
fn thesis_dir(parent: &Path, name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = parent.join(name);
    std::fs::create_dir_all(&dir).unwrap();
    let mut all = vec![
        ("scene.sod", SOD),
        ("objects.txt", "# geometry object\nplane.geo plane.ood\n"),
        ("plane.ood", OOD),
        ("plane.geo", GEO),
    ];
    for (file, text) in files {
        match all.iter_mut().find(|(f, _)| f == file) {
            Some(entry) => entry.1 = text,
            None => all.push((file, text)),
        }
    }
    for (file, text) in all {
        std::fs::write(dir.join(file), text).unwrap();
    }
    dir
}

#[test]
fn malformed_thesis_scene_directories_name_the_file_the_line_and_the_token() {
    let tmp = tmp();
    let out_png = at(&tmp, "x.png");

    // The well-formed directory renders at its .sod's size.
    let good = thesis_dir(tmp.path(), "good", &[]);
    rtfpga(&["render", "--scene", s(&good), "--quiet"])
        .out(&out_png)
        .ok();
    let img = read_png(&out_png);
    assert_eq!(img.dimensions(), (32, 18), "the .sod's width and height");
    let background = Rgb([51, 77, 102]);
    assert!(
        img.pixels()
            .any(|p| p.0.iter().zip(background.0).any(|(a, b)| a.abs_diff(b) > 2)),
        "the plane is in view"
    );
    std::fs::remove_file(&out_png).unwrap();

    let geo_bad_normal = GEO.replace("0 1 0  0 1 0  0 1 0  0 1 0", "0 1 0  0 one 0  0 1 0  0 1 0");
    let geo_short = GEO.replace("0 0  1 0  1 1  0 1", "0 0  1 0  1 1");
    let ood_bad_kind = OOD.replace("0 1 0.18", "7 1 0.18");
    let sod_bad_fov = SOD.replace("32 18 40", "32 18 200");
    let sod_zero_width = SOD.replace("32 18 40", "0 18 40");
    let cases: Vec<(&str, (&str, &str), Vec<&str>)> = vec![
        (
            "normal",
            ("plane.geo", &geo_bad_normal),
            vec!["plane.geo:5", "`one`", "normal 2 of 4"],
        ),
        (
            "short",
            ("plane.geo", &geo_short),
            vec!["plane.geo:6", "end of file", "texture coordinate 4 of 4"],
        ),
        (
            "material",
            ("plane.ood", &ood_bad_kind),
            vec!["plane.ood:5", "`7`", "material type"],
        ),
        (
            "fov",
            ("scene.sod", &sod_bad_fov),
            vec!["scene.sod:2", "`200`", "fov"],
        ),
        (
            "width",
            ("scene.sod", &sod_zero_width),
            vec!["scene.sod:2", "`0`", "image width"],
        ),
        (
            "list",
            (
                "objects.txt",
                "# geometry object\nplane.geo plane.ood extra\n",
            ),
            vec!["objects.txt:2", "plane.geo plane.ood extra", "2 file names"],
        ),
        (
            "missing_geo",
            ("objects.txt", "plane.geo plane.ood\nnone.geo plane.ood\n"),
            vec!["none.geo", "cannot read"],
        ),
        (
            "empty_list",
            ("objects.txt", "# nothing\n"),
            vec!["objects.txt", "no objects"],
        ),
    ];
    for (name, file, needles) in cases {
        let dir = thesis_dir(tmp.path(), name, &[file]);
        rtfpga(&["render", "--scene", s(&dir)])
            .out(&out_png)
            .fails(1, &needles);
    }
    // A directory without its .sod.
    let dir = thesis_dir(tmp.path(), "no_sod", &[]);
    std::fs::remove_file(dir.join("scene.sod")).unwrap();
    rtfpga(&["render", "--scene", s(&dir)])
        .out(&out_png)
        .fails(1, &["no_sod", ".sod"]);
    assert!(!out_png.exists());
}

#[test]
fn a_scene_file_asking_for_zero_pixels_is_refused_at_its_line() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    let toml = at(&dir, "empty.toml");
    std::fs::write(
        &toml,
        simple_plane_toml().replace("width = 640", "width = 0"),
    )
    .unwrap();
    rtfpga(&["render", "--scene", s(&toml)])
        .out(&png)
        .fails(1, &["empty.toml:7", "at least 1 pixel", "`0`"]);
    assert!(!png.exists());
}
