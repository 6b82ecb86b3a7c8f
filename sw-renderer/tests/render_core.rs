//! The renderer against hand-computed pixels, against a literal recursive port of the
//! reference's castRay/trace (brute force, no BVH, no wavefront), and for invariance under
//! thread count and batch splitting. Scenes are built in code.

use std::f32::consts::PI;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use glam::{Vec2, Vec3};
use image::{Rgb, RgbImage};
use sw_renderer::camera::{fov_scale, Camera};
use sw_renderer::compare::{compare, diff_heatmap, psnr, CompareError};
use sw_renderer::hit::{Hit, NO_BOUND};
use sw_renderer::intersect::{F32Intersector, Intersector, MtQuery, MtResult};
use sw_renderer::math::V3;
use sw_renderer::rays::EngineError;
use sw_renderer::render::{render, RenderError, RenderOptions};
use sw_renderer::scene::{
    Light, LightKind, Mat44, Material, MaterialKind, Mesh, Object, Options, Scene,
};
use sw_renderer::shade::{
    diffuse_colour, fresnel, fresnel_colour, hit_normal, hit_point, mirror_colour, phong_colour,
    reflect, refract, to_rgb8, LightTerm, PreparedLight,
};
use sw_renderer::world::World;

mod common;
use common::brute_force_trace;

// ---------------------------------------------------------------- scene building

fn translation(x: f32, y: f32, z: f32) -> Mat44 {
    let mut m = Mat44::IDENTITY;
    m.0[3] = [x, y, z, 1.0];
    m
}

/// Maps (0, 0, −1) to (0, 0, +1): a distant light shining up, or a quad facing down.
fn flip_z() -> Mat44 {
    Mat44([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, -1.0, 0.0, 0.0],
        [0.0, 0.0, -1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ])
}

/// A square in the plane z = 0 facing +z, corners at ±half.
fn quad(half: f32) -> Mesh {
    let p = |x: f32, y: f32| Vec3::new(x * half, y * half, 0.0);
    let n = [Vec3::Z; 3];
    Mesh {
        positions: vec![p(-1.0, -1.0), p(1.0, -1.0), p(1.0, 1.0), p(-1.0, 1.0)],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        normals: vec![n, n],
        uvs: vec![[Vec2::ZERO; 3]; 2],
    }
}

/// A UV sphere of radius 1 with smooth normals.
fn sphere(rings: u32, segments: u32) -> Mesh {
    let mut positions = Vec::new();
    for r in 0..=rings {
        let theta = PI * r as f32 / rings as f32;
        for s in 0..segments {
            let phi = 2.0 * PI * s as f32 / segments as f32;
            positions.push(Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ));
        }
    }
    let idx = |r: u32, s: u32| r * segments + s % segments;
    let mut triangles = Vec::new();
    for r in 0..rings {
        for s in 0..segments {
            triangles.push([idx(r, s), idx(r + 1, s), idx(r + 1, s + 1)]);
            triangles.push([idx(r, s), idx(r + 1, s + 1), idx(r, s + 1)]);
        }
    }
    let normals = triangles
        .iter()
        .map(|t| t.map(|i| positions[i as usize].normalize()))
        .collect();
    let uvs = vec![[Vec2::ZERO; 3]; triangles.len()];
    Mesh {
        positions,
        triangles,
        normals,
        uvs,
    }
}

fn material(kind: MaterialKind) -> Material {
    Material {
        kind,
        ior: 1.5,
        albedo: Vec3::new(0.6, 0.5, 0.4),
        kd: 0.8,
        ks: 0.2,
        n: 10.0,
    }
}

fn object(name: &str, mesh: Mesh, object_to_world: Mat44, material: Material) -> Object {
    Object {
        name: name.to_string(),
        mesh: Arc::new(mesh),
        object_to_world,
        material,
    }
}

fn distant(color: Vec3, intensity: f32, light_to_world: Mat44) -> Light {
    Light {
        kind: LightKind::Distant,
        color,
        intensity,
        light_to_world,
    }
}

fn point(color: Vec3, intensity: f32, at: [f32; 3]) -> Light {
    Light {
        kind: LightKind::Point,
        color,
        intensity,
        light_to_world: translation(at[0], at[1], at[2]),
    }
}

/// A camera at (0, 0, 5) looking down −z at an odd-sized image (the centre pixel looks
/// exactly along −z).
fn scene(objects: Vec<Object>, lights: Vec<Light>) -> Scene {
    Scene {
        name: "test".to_string(),
        options: Options {
            width: 5,
            height: 5,
            fov_deg: 30.0,
            background: Vec3::ZERO,
            camera_to_world: translation(0.0, 0.0, 5.0),
            bias: 1e-4,
            max_depth: 4,
        },
        lights,
        objects,
    }
}

fn render_f32(scene: &Scene) -> RgbImage {
    render(scene, &F32Intersector, &RenderOptions::default())
        .unwrap()
        .image
}

fn centre(img: &RgbImage) -> [u8; 3] {
    img.get_pixel(img.width() / 2, img.height() / 2).0
}

/// What the reference wrote for a colour: `(char)(255 * clamp(0, 1, x))`.
fn byte(x: f32) -> u8 {
    (255.0 * x.clamp(0.0, 1.0)) as u8
}

// ---------------------------------------------------------------- camera

#[test]
fn camera_rays_follow_the_reference_formulas() {
    assert_eq!(fov_scale(90.0), 1.0);
    let cam = Camera::new(Mat44::IDENTITY, 90.0, 4, 2);
    // x = (2·0.5/4 − 1)·2·1 = −1.5, y = (1 − 2·0.5/2)·1 = 0.5.
    assert_eq!(cam.screen(0, 0), (-1.5, 0.5));
    assert_eq!(cam.screen(3, 1), (1.5, -0.5));
    let d = cam.direction(0, 0);
    let n = (1.5f64 * 1.5 + 0.25 + 1.0).sqrt() as f32;
    for (got, want) in [d.x, d.y, d.z].iter().zip([-1.5 / n, 0.5 / n, -1.0 / n]) {
        assert!((got - want).abs() <= 1e-7, "{d:?}");
    }
    // A translated camera keeps directions, moves the origin; a rotated one turns them.
    let cam = Camera::new(translation(1.0, 2.0, 3.0), 90.0, 4, 2);
    assert_eq!(cam.origin, V3::new(1.0, 2.0, 3.0));
    assert_eq!(cam.direction(0, 0), d);
    let cam = Camera::new(flip_z(), 90.0, 4, 2);
    assert_eq!(cam.direction(0, 0), V3::new(d.x, -d.y, -d.z));
    // The double evaluation: (2·(i+0.5)/w − 1)·aspect·scale rounded once.
    let cam = Camera::new(Mat44::IDENTITY, 37.0, 1920, 1080);
    let scale = f64::from(fov_scale(37.0));
    let aspect = f64::from(1920.0f32 / 1080.0);
    let want = ((2.0 * 777.5 / 1920.0 - 1.0) * aspect * scale) as f32;
    assert_eq!(cam.screen(777, 0).0, want);
}

// ---------------------------------------------------------------- materials, by hand

#[test]
fn diffuse_plane_under_a_distant_light() {
    // Light straight down: N·(−L) = 1, colour = 0.9 · colour · intensity.
    let plane = object(
        "plane",
        quad(100.0),
        Mat44::IDENTITY,
        material(MaterialKind::Diffuse),
    );
    let s = scene(
        vec![plane.clone()],
        vec![distant(Vec3::new(1.0, 0.5, 0.25), 0.5, Mat44::IDENTITY)],
    );
    let img = render_f32(&s);
    let want = [byte(0.9 * 0.5), byte(0.9 * 0.25), byte(0.9 * 0.125)];
    assert_eq!(want, [114, 57, 28]);
    assert!(
        img.pixels().all(|p| p.0 == want),
        "{:?}",
        img.pixels().collect::<Vec<_>>()
    );

    // Tilted by 60° about x: cos = 0.5.
    let (sin, cos) = (60.0f32.to_radians().sin(), 60.0f32.to_radians().cos());
    let tilt = Mat44([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, cos, sin, 0.0],
        [0.0, -sin, cos, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]);
    let s = scene(vec![plane.clone()], vec![distant(Vec3::ONE, 1.0, tilt)]);
    let c = centre(&render_f32(&s));
    assert!(
        c.iter()
            .all(|&x| x == byte(0.9 * 0.5) || x == byte(0.9 * 0.5) - 1),
        "{c:?}"
    );

    // Lit from below: nothing.
    let s = scene(vec![plane], vec![distant(Vec3::ONE, 1.0, flip_z())]);
    assert_eq!(centre(&render_f32(&s)), [0, 0, 0]);
}

#[test]
fn shadows_are_cast_except_by_glass() {
    // A small square hovers at z = 1 over a lit plane; the light comes in at 45° so the
    // shadow falls beside the square. Plane pixels outside the square's own footprint are
    // either lit (0.9·cos 45°) or in shadow (0).
    let plane = object(
        "plane",
        quad(100.0),
        Mat44::IDENTITY,
        material(MaterialKind::Diffuse),
    );
    let occluder = |kind| {
        object(
            "occluder",
            quad(0.3),
            translation(0.0, 0.0, 1.0),
            material(kind),
        )
    };
    let r = std::f32::consts::FRAC_1_SQRT_2;
    let tilt = Mat44([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, r, r, 0.0],
        [0.0, -r, r, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]);
    let mut s = scene(
        vec![plane, occluder(MaterialKind::Phong)],
        vec![distant(Vec3::ONE, 1.0, tilt)],
    );
    s.options.width = 41;
    s.options.height = 41;
    s.options.fov_deg = 60.0;
    let footprint: Vec<bool> = render_f32(&Scene {
        objects: vec![occluder(MaterialKind::Diffuse)],
        ..s.clone()
    })
    .pixels()
    .map(|p| p.0 != [0, 0, 0])
    .collect();
    let lit = [byte(0.9 * r); 3];
    let count = |img: &RgbImage, colour: [u8; 3]| {
        img.pixels()
            .zip(&footprint)
            .filter(|(p, &inside)| !inside && p.0 == colour)
            .count()
    };
    let opaque = render_f32(&s);
    let outside = footprint.iter().filter(|&&f| !f).count();
    assert!(count(&opaque, [0, 0, 0]) > 10, "no shadow");
    assert_eq!(count(&opaque, [0, 0, 0]) + count(&opaque, lit), outside);

    s.objects[1] = occluder(MaterialKind::ReflectionRefraction);
    let glass = render_f32(&s);
    assert_eq!(count(&glass, [0, 0, 0]), 0, "glass must not cast a shadow");
    assert_eq!(count(&glass, lit), outside);
}

#[test]
fn point_light_falls_off_with_the_square_of_the_distance() {
    let plane = object(
        "plane",
        quad(100.0),
        Mat44::IDENTITY,
        material(MaterialKind::Diffuse),
    );
    let at = |h: f32| {
        scene(
            vec![plane.clone()],
            vec![point(Vec3::ONE, 10.0, [0.0, 0.0, h])],
        )
    };
    // Centre pixel hits (0, 0, 0) straight below the light: I = 10 / float(4π r²), cos = 1.
    let i1 = 10.0f32 / (4.0 * std::f64::consts::PI) as f32;
    let i2 = 10.0f32 / (16.0 * std::f64::consts::PI) as f32;
    assert_eq!(centre(&render_f32(&at(1.0))), [byte(0.9 * i1); 3]);
    assert_eq!(centre(&render_f32(&at(2.0))), [byte(0.9 * i2); 3]);
    assert_eq!((byte(0.9 * i1), byte(0.9 * i2)), (182, 45));
}

#[test]
fn mirror_reflects_with_weight_point_eight() {
    let mirror = object(
        "mirror",
        quad(100.0),
        Mat44::IDENTITY,
        material(MaterialKind::Reflection),
    );
    // Only background in the reflection: 0.8 · background.
    let mut s = scene(vec![mirror.clone()], vec![]);
    s.options.background = Vec3::new(0.5, 0.25, 1.0);
    let img = render_f32(&s);
    assert!(img
        .pixels()
        .all(|p| p.0 == [byte(0.4), byte(0.2), byte(0.8)]));
    // A wall facing down at z = 10 behind the camera, lit by a point light at z = 8 (its
    // shadow ray is bounded by the distance 2, so the mirror does not occlude it).
    let wall = object(
        "wall",
        quad(100.0),
        {
            let mut m = flip_z();
            m.0[3] = [0.0, 0.0, 10.0, 1.0];
            m
        },
        material(MaterialKind::Diffuse),
    );
    let s = scene(
        vec![mirror, wall],
        vec![point(Vec3::ONE, 10.0, [0.0, 0.0, 8.0])],
    );
    let i = 10.0f32 / (16.0 * std::f64::consts::PI) as f32;
    assert_eq!(centre(&render_f32(&s)), [byte(0.8 * 0.9 * i); 3]);
    assert_eq!(byte(0.8 * 0.9 * i), 36);
}

#[test]
fn glass_mixes_reflection_and_refraction_by_fresnel() {
    // Normal incidence on ior 1.5: kr = ((1.5 − 1)/(1.5 + 1))² = 0.04. Behind the glass a
    // diffuse plane lit by a yellow light straight down (the glass casts no shadow);
    // in front only the blue background.
    let glass = object(
        "glass",
        quad(100.0),
        Mat44::IDENTITY,
        material(MaterialKind::ReflectionRefraction),
    );
    let floor = object(
        "floor",
        quad(100.0),
        translation(0.0, 0.0, -1.0),
        material(MaterialKind::Diffuse),
    );
    let mut s = scene(
        vec![glass, floor],
        vec![distant(Vec3::new(1.0, 1.0, 0.0), 1.0, Mat44::IDENTITY)],
    );
    s.options.background = Vec3::new(0.0, 0.0, 1.0);
    let c = centre(&render_f32(&s));
    assert_eq!(c, [byte(0.9 * 0.96), byte(0.9 * 0.96), byte(0.04)]);
    assert_eq!(c, [220, 220, 10]);
    // With max depth 0 both secondary rays return the background: blue.
    s.options.max_depth = 0;
    assert_eq!(centre(&render_f32(&s)), [0, 0, 255]);
}

#[test]
fn phong_highlight_peaks_where_the_reflection_meets_the_eye() {
    let mut m = material(MaterialKind::Phong);
    m.albedo = Vec3::splat(0.5);
    m.kd = 0.5;
    m.ks = 0.2;
    let plane = object("plane", quad(100.0), Mat44::IDENTITY, m);
    let mut s = scene(vec![plane], vec![distant(Vec3::ONE, 1.0, Mat44::IDENTITY)]);
    s.options.width = 9;
    s.options.height = 9;
    let img = render_f32(&s);
    // Colour = (albedo · I · cos)·Kd + (I · (R·(−d))^n)·Ks with R = (0, 0, 1), cos = 1.
    let cam = Camera::new(s.options.camera_to_world, s.options.fov_deg, 9, 9);
    for i in 0..9 {
        let d = cam.direction(i, 4);
        let want = byte(0.25 + 0.2 * (-d.z).powf(10.0));
        assert_eq!(img.get_pixel(i, 4).0, [want; 3], "pixel {i}");
    }
    assert_eq!(centre(&img), [byte(0.45); 3]);
    assert!(img.get_pixel(0, 4).0[0] < img.get_pixel(4, 4).0[0]);
}

// ---------------------------------------------------------------- against the recursive reference

/// The reference's `trace` over the world; shadow rays pass through transparent objects.
fn ref_trace(world: &World, orig: V3, dir: V3, bound: f32, shadow: bool) -> Option<Hit> {
    brute_force_trace(&world.triangles, orig, dir, bound, |k| {
        shadow && world.materials[k].kind == MaterialKind::ReflectionRefraction
    })
}

/// The reference's recursive `castRay`.
fn ref_cast(
    s: &Scene,
    world: &World,
    lights: &[PreparedLight],
    orig: V3,
    dir: V3,
    depth: u32,
) -> V3 {
    let bg = V3::from(s.options.background);
    if depth > s.options.max_depth {
        return bg;
    }
    let Some(hit) = ref_trace(world, orig, dir, NO_BOUND, false) else {
        return bg;
    };
    let tri = &world.triangles[hit.triangle as usize];
    let m = &world.materials[tri.object as usize];
    let p = hit_point(orig, dir, &hit);
    let n = hit_normal(tri, &hit);
    let bias = s.options.bias;
    let lit = |phong: bool| {
        lights
            .iter()
            .map(|l| {
                let il = l.illuminate(p);
                let vis = ref_trace(world, p + n * bias, -il.dir, il.distance, true).is_none();
                let term = if phong {
                    LightTerm::phong(&il, n, dir, m.n)
                } else {
                    LightTerm::diffuse(&il, n)
                };
                (term, vis)
            })
            .collect::<Vec<_>>()
    };
    match m.kind {
        MaterialKind::Diffuse => diffuse_colour(lit(false).into_iter()),
        MaterialKind::Phong => phong_colour(lit(true).into_iter(), V3::from(m.albedo), m.kd, m.ks),
        MaterialKind::Reflection => {
            let r = reflect(dir, n).normalized();
            mirror_colour(ref_cast(s, world, lights, p + n * bias, r, depth + 1))
        }
        MaterialKind::ReflectionRefraction => {
            let kr = fresnel(dir, n, m.ior);
            let outside = dir.dot(n) < 0.0;
            let b = n * bias;
            let mut refraction = V3::ZERO;
            if kr < 1.0 {
                let d = refract(dir, n, m.ior).normalized();
                refraction = ref_cast(
                    s,
                    world,
                    lights,
                    if outside { p - b } else { p + b },
                    d,
                    depth + 1,
                );
            }
            let d = reflect(dir, n).normalized();
            let reflection = ref_cast(
                s,
                world,
                lights,
                if outside { p + b } else { p - b },
                d,
                depth + 1,
            );
            fresnel_colour(reflection, refraction, kr)
        }
    }
}

fn ref_render(s: &Scene) -> RgbImage {
    let world = World::new(s).unwrap();
    let lights: Vec<_> = s.lights.iter().map(PreparedLight::new).collect();
    let cam = Camera::new(
        s.options.camera_to_world,
        s.options.fov_deg,
        s.options.width,
        s.options.height,
    );
    RgbImage::from_fn(s.options.width, s.options.height, |i, j| {
        Rgb(to_rgb8(ref_cast(
            s,
            &world,
            &lights,
            cam.origin,
            cam.direction(i, j),
            0,
        )))
    })
}

/// Every material, both light kinds, transformed meshes, a closed glass sphere (refraction
/// inside, total internal reflection), mirrors seeing glass and each other.
fn all_materials_scene() -> Scene {
    let scaled = |s: f32, at: [f32; 3]| {
        Mat44([
            [s, 0.0, 0.0, 0.0],
            [0.0, s, 0.0, 0.0],
            [0.0, 0.0, s, 0.0],
            [at[0], at[1], at[2], 1.0],
        ])
    };
    let tilted_mirror = Mat44([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 0.8, 0.6, 0.0],
        [0.0, -0.6, 0.8, 0.0],
        [0.0, 2.0, -3.0, 1.0],
    ]);
    let mut glass = material(MaterialKind::ReflectionRefraction);
    glass.ior = 1.3;
    let mut s = scene(
        vec![
            object(
                "floor",
                quad(8.0),
                translation(0.0, 0.0, -2.0),
                material(MaterialKind::Diffuse),
            ),
            object(
                "glass ball",
                sphere(8, 14),
                scaled(0.9, [-0.8, 0.0, -0.5]),
                glass,
            ),
            object(
                "phong ball",
                sphere(7, 12),
                scaled(0.7, [1.0, 0.3, -1.0]),
                material(MaterialKind::Phong),
            ),
            object(
                "mirror",
                quad(2.0),
                tilted_mirror,
                material(MaterialKind::Reflection),
            ),
            // Non-uniform scale: normals need the inverse transpose.
            object(
                "squashed",
                sphere(6, 10),
                Mat44([
                    [0.5, 0.0, 0.0, 0.0],
                    [0.0, 1.2, 0.0, 0.0],
                    [0.0, 0.0, 0.3, 0.0],
                    [0.5, -1.4, -1.2, 1.0],
                ]),
                material(MaterialKind::Diffuse),
            ),
        ],
        vec![
            distant(
                Vec3::new(1.0, 0.9, 0.8),
                0.8,
                Mat44([
                    [1.0, 0.0, 0.0, 0.0],
                    [0.0, 0.8, 0.6, 0.0],
                    [0.0, -0.6, 0.8, 0.0],
                    [0.0, 0.0, 0.0, 1.0],
                ]),
            ),
            point(Vec3::new(0.6, 0.7, 1.0), 300.0, [2.0, 3.0, 3.0]),
        ],
    );
    s.options.width = 64;
    s.options.height = 48;
    s.options.fov_deg = 50.0;
    s.options.background = Vec3::new(0.2, 0.4, 0.7);
    s.options.max_depth = 5;
    s
}

#[test]
fn wavefront_render_equals_the_recursive_reference_bit_for_bit() {
    let s = all_materials_scene();
    let got = render(
        &s,
        &F32Intersector,
        &RenderOptions {
            tile_size: 16,
            ..Default::default()
        },
    )
    .unwrap();
    let want = ref_render(&s);
    let diff = compare(&got.image, &want).unwrap();
    assert_eq!(diff.differing_pixels, 0, "{diff:?}");
    // The scene really exercises every path.
    let st = got.stats.trace;
    assert!(
        st.reflection_rays > 100 && st.refraction_rays > 100 && st.shadow_rays > 1000,
        "{st:?}"
    );
    assert_eq!(st.primary_rays, 64 * 48);
    // Distinct colours: not a blank image.
    let mut colours: Vec<[u8; 3]> = got.image.pixels().map(|p| p.0).collect();
    colours.sort();
    colours.dedup();
    assert!(colours.len() > 500, "{} colours", colours.len());
}

/// The thesis' scenes, small, against the recursive reference (skipped, with a line on
/// stderr, when the thesis scenes are not found: `sw_renderer::thesis_scenes`).
#[test]
fn thesis_scenes_equal_the_recursive_reference() {
    let Some(root) = sw_renderer::thesis_scenes::for_test(
        "render_core::thesis_scenes_equal_the_recursive_reference",
    ) else {
        return;
    };
    for name in sw_renderer::thesis_scenes::SCENE_DIRS {
        let dir = root.join(name);
        let mut s = Scene::load(dir.to_str().unwrap()).unwrap();
        let (w, h) = (s.options.width, s.options.height);
        // A small image of the same aspect and field of view.
        s.options.width = 32;
        s.options.height = (32 * h / w).max(1);
        let got = render_f32(&s);
        let want = ref_render(&s);
        assert_eq!(compare(&got, &want).unwrap().differing_pixels, 0, "{name}");
    }
}

// ---------------------------------------------------------------- invariance

#[test]
fn image_does_not_depend_on_thread_count_or_tile_size() {
    let s = all_materials_scene();
    let in_pool = |threads: usize, tile_size: u32| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            render(
                &s,
                &F32Intersector,
                &RenderOptions {
                    tile_size,
                    ..Default::default()
                },
            )
            .unwrap()
        })
    };
    let one = in_pool(1, 32);
    let two = in_pool(2, 32);
    let two_small = in_pool(2, 7);
    assert_eq!(one.image, two.image);
    assert_eq!(one.image, two_small.image);
    assert_eq!(one.stats.trace.cast, two.stats.trace.cast);
}

/// Splits every batch into chunks of a few queries: results must not depend on batch borders.
struct Splitting {
    chunk: usize,
    calls: AtomicU64,
}

impl Intersector for Splitting {
    fn name(&self) -> String {
        format!("f32 split {}", self.chunk)
    }
    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), EngineError> {
        for (q, r) in queries
            .chunks(self.chunk)
            .zip(results.chunks_mut(self.chunk))
        {
            self.calls.fetch_add(1, Ordering::Relaxed);
            F32Intersector.intersect_batch(q, r)?;
        }
        Ok(())
    }
}

/// Answers `ok_batches` batches, then fails: as a co-simulation that breaks mid-render.
struct Failing {
    ok_batches: u64,
    calls: AtomicU64,
}

impl Intersector for Failing {
    fn name(&self) -> String {
        "failing".to_string()
    }
    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), EngineError> {
        if self.calls.fetch_add(1, Ordering::Relaxed) >= self.ok_batches {
            return Err("simulated instance stopped answering".into());
        }
        F32Intersector.intersect_batch(queries, results)
    }
}

#[test]
fn an_engine_error_ends_the_render_as_an_error_not_as_misses() {
    let s = all_materials_scene();
    for ok_batches in [0, 3] {
        let failing = Failing {
            ok_batches,
            calls: AtomicU64::new(0),
        };
        let err = render(&s, &failing, &RenderOptions::default()).unwrap_err();
        let text = err.to_string();
        assert!(
            matches!(err, RenderError::Engine { .. })
                && text.contains("failing")
                && text.contains("simulated instance stopped answering"),
            "{text}"
        );
    }
}

#[test]
fn image_does_not_depend_on_batch_boundaries() {
    let s = all_materials_scene();
    let whole = render(&s, &F32Intersector, &RenderOptions::default()).unwrap();
    let split = Splitting {
        chunk: 5,
        calls: AtomicU64::new(0),
    };
    let parts = render(&s, &split, &RenderOptions::default()).unwrap();
    assert_eq!(whole.image, parts.image);
    assert!(split.calls.load(Ordering::Relaxed) > 3 * parts.stats.trace.cast.batches);
}

#[test]
fn width_and_height_override_the_scene() {
    let s = all_materials_scene();
    let out = render(
        &s,
        &F32Intersector,
        &RenderOptions {
            width: Some(20),
            height: Some(10),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(out.image.dimensions(), (20, 10));
    assert!(render(
        &s,
        &F32Intersector,
        &RenderOptions {
            width: Some(0),
            ..Default::default()
        }
    )
    .is_err());
}

// ---------------------------------------------------------------- image comparison

#[test]
fn psnr_of_identical_known_and_mismatched_images() {
    let a = RgbImage::from_fn(8, 4, |i, j| Rgb([(i * 20) as u8, (j * 40) as u8, 100]));
    assert_eq!(psnr(&a, &a).unwrap(), f64::INFINITY);
    // Every sample off by one: MSE = 1, PSNR = 10·log10(255²) = 48.1308 dB.
    let b = RgbImage::from_fn(8, 4, |i, j| {
        Rgb([(i * 20) as u8 + 1, (j * 40) as u8 + 1, 99])
    });
    let d = compare(&a, &b).unwrap();
    assert_eq!(d.mse, 1.0);
    assert!((d.psnr_db - 48.130_803_6).abs() < 1e-6, "{}", d.psnr_db);
    assert_eq!((d.differing_share, d.max_abs_error), (1.0, 1));
    // One sample off by 12 in 96 samples: MSE = 1.5.
    let mut c = a.clone();
    c.get_pixel_mut(3, 2).0[1] += 12;
    let d = compare(&a, &c).unwrap();
    assert_eq!(d.mse, 1.5);
    assert!((d.psnr_db - 10.0 * (65025.0f64 / 1.5).log10()).abs() < 1e-9);
    assert_eq!((d.differing_pixels, d.max_abs_error), (1, 12));
    let small = RgbImage::new(4, 4);
    assert_eq!(
        psnr(&a, &small),
        Err(CompareError::SizeMismatch {
            a_width: 8,
            a_height: 4,
            b_width: 4,
            b_height: 4
        })
    );
    assert!(diff_heatmap(&a, &small).is_err());
}

#[test]
fn heatmap_is_black_exactly_where_images_agree() {
    let a = RgbImage::from_fn(6, 6, |i, j| Rgb([(i * 30) as u8, (j * 30) as u8, 7]));
    assert!(diff_heatmap(&a, &a)
        .unwrap()
        .pixels()
        .all(|p| p.0 == [0, 0, 0]));
    let mut b = a.clone();
    b.get_pixel_mut(2, 3).0[2] = 8;
    b.get_pixel_mut(5, 0).0[0] = 255;
    let h = diff_heatmap(&a, &b).unwrap();
    for (i, j, p) in h.enumerate_pixels() {
        let differs = (i, j) == (2, 3) || (i, j) == (5, 0);
        assert_eq!(p.0 != [0, 0, 0], differs, "({i}, {j})");
    }
    // Bigger errors are redder.
    assert!(h.get_pixel(5, 0).0[0] > h.get_pixel(2, 3).0[0]);
}
