//! What the commands print and write: `key=value` lines that split alike (values with spaces
//! quoted), the path of what was written, output folders made and image paths checked
//! before any work.

use crate::common::*;

#[test]
fn values_with_spaces_are_quoted_and_every_line_splits_alike() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    let out = render("simple_plane", 8, 8, &png)
        .args(&["--engine", "model", "--format", "fp16"])
        .ok();
    assert!(out.contains(r#" engine="model fp16" "#), "{out}");
    let out = render("simple_plane", 8, 8, &png)
        .args(&["--engine", "model", "--format", "bfp18/fp32"])
        .ok();
    assert!(out.contains(r#" engine="model bfp18/fp32" "#), "{out}");
    let (label, fields) = fields(labelled(&out, "dual_precision")).unwrap();
    assert_eq!(label.as_deref(), Some("dual_precision"));
    assert!(
        fields.iter().any(|(k, v)| k == "pair" && v == "bfp18/fp32"),
        "{out}"
    );
}

#[test]
fn render_prints_the_path_it_wrote_and_makes_its_folder() {
    let dir = tmp();
    let png = at(&dir, "new/deeper/x.png");
    let out = render("simple_plane", 8, 8, &png).ok();
    assert_eq!(value(&out, "out").as_deref(), Some(s(&png)), "{out}");
    assert_eq!(read_png(&png).dimensions(), (8, 8));
    // A relative path is printed absolute.
    let out = render("simple_plane", 8, 8, std::path::Path::new("rel.png"))
        .command()
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(
        value(&stdout, "out"),
        Some(s(&at(&dir, "rel.png")).to_string()),
        "{stdout}"
    );
}

#[test]
fn an_image_path_that_is_not_png_is_refused_before_any_work() {
    let dir = tmp();
    for name in ["x.jpg", "x", "x.png.txt"] {
        let path = at(&dir, &format!("new/{name}"));
        render("utah_teapot", 16, 16, &path).fails(1, &[name, ".png"]);
        cosim("utah_teapot", 16, 16, &path).fails(1, &[name, ".png"]);
        let png = at(&dir, "a.png");
        render("simple_plane", 4, 4, &png).ok();
        rtfpga(&["compare", s(&png), s(&png), "--diff", s(&path)]).fails(1, &["--diff", name]);
        rtfpga(&["compare", s(&png), s(&png), "--side-by-side", s(&path)])
            .fails(1, &["--side-by-side", name]);
    }
    assert!(
        !at(&dir, "new").exists(),
        "no folder made for a refused path"
    );
}

#[test]
fn an_output_into_a_file_that_is_not_a_folder_is_refused_before_any_work() {
    let dir = tmp();
    let file = at(&dir, "file");
    std::fs::write(&file, "x").unwrap();
    let png = file.join("x.png");
    render("simple_plane", 8, 8, &png).fails(1, &["creating the folder", "file"]);
    rtfpga(&["verilog"])
        .out(&file.join("v"))
        .fails(1, &["creating the folder"]);
    rtfpga(&["scene-image", "--scene", "simple_plane"])
        .out(&file.join("s.rtsi"))
        .fails(1, &["creating the folder"]);
}

#[test]
fn compare_prints_the_paths_it_wrote() {
    let dir = tmp();
    let png = at(&dir, "a.png");
    render("simple_plane", 4, 4, &png).ok();
    let (d, m) = (at(&dir, "out/d.png"), at(&dir, "out/m.png"));
    let out = rtfpga(&[
        "compare",
        s(&png),
        s(&png),
        "--diff",
        s(&d),
        "--side-by-side",
        s(&m),
    ])
    .ok();
    assert_eq!(value(&out, "diff").as_deref(), Some(s(&d)), "{out}");
    assert_eq!(value(&out, "side_by_side").as_deref(), Some(s(&m)), "{out}");
    assert_eq!(last_line(&out), "psnr_db=inf");
}
