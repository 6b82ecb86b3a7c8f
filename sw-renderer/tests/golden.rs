//! The committed golden images are exactly what the renderer produces now.

use sw_renderer::golden::{render_builtin, HEIGHT, WIDTH};
use sw_renderer::scene::builtin;

#[test]
fn golden_images_are_current() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../golden");
    let manifest = std::fs::read_to_string(dir.join("manifest.toml"))
        .expect("golden/manifest.toml (run `make golden`)");
    for name in builtin::names() {
        assert!(
            manifest.contains(&format!("scene = \"{name}\"")),
            "{name} missing from golden/manifest.toml"
        );
        let path = dir.join(format!("{name}.png"));
        let golden = image::open(&path)
            .unwrap_or_else(|e| panic!("{}: {e} (run `make golden`)", path.display()))
            .to_rgb8();
        assert_eq!(golden.dimensions(), (WIDTH, HEIGHT), "{}", path.display());
        let now = render_builtin(name).unwrap();
        let diff = sw_renderer::compare::compare(&golden, &now).unwrap();
        assert_eq!(
            diff.differing_pixels,
            0,
            "{} is stale: {} pixels differ (run `make golden`)",
            path.display(),
            diff.differing_pixels
        );
    }
}

/// Every project scene renders to the same pixels on 1 and on 2 threads.
#[test]
fn project_scenes_are_deterministic_across_thread_counts() {
    use sw_renderer::intersect::F32Intersector;
    use sw_renderer::render::{render, RenderOptions};
    use sw_renderer::scene::Scene;
    let opts = RenderOptions {
        width: Some(96),
        height: Some(54),
        tile_size: 8,
        ..Default::default()
    };
    for name in builtin::names() {
        let scene = Scene::load(name).unwrap();
        let on = |threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| render(&scene, &F32Intersector, &opts).unwrap().image)
        };
        assert!(
            on(1) == on(2),
            "{name}: 1-thread and 2-thread renders differ"
        );
    }
}
