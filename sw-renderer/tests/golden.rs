//! The committed golden images are exactly what the renderer produces now.

use sw_renderer::golden::{render_builtin, HEIGHT, WIDTH};
use sw_renderer::scene::builtin;

#[test]
fn golden_images_are_current() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../golden");
    let manifest = std::fs::read_to_string(dir.join("manifest.toml")).expect("golden/manifest.toml (run `make golden`)");
    for name in builtin::names() {
        assert!(manifest.contains(&format!("scene = \"{name}\"")), "{name} missing from golden/manifest.toml");
        let path = dir.join(format!("{name}.png"));
        let golden = image::open(&path).unwrap_or_else(|e| panic!("{}: {e} (run `make golden`)", path.display())).to_rgb8();
        assert_eq!(golden.dimensions(), (WIDTH, HEIGHT), "{}", path.display());
        let now = render_builtin(name).unwrap();
        let diff = sw_renderer::compare::compare(&golden, &now).unwrap();
        assert_eq!(diff.differing_pixels, 0, "{} is stale: {} pixels differ (run `make golden`)", path.display(), diff.differing_pixels);
    }
}
