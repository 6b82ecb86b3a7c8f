//! Wavefront Whitted tracing of a group of primary rays.
//!
//! The reference recursed ray by ray (castRay → trace → castRay …). Here the same recursion
//! is unrolled into a ray tree built breadth first: level 0 holds the primary rays; every hit
//! of a level adds its shadow rays (one per light) and its secondary rays (reflection, Fresnel
//! reflection and refraction) to the next level. Each level is one wavefront for the ray
//! caster (`rays`), which returns the reference's hits. Colours are finally evaluated
//! bottom-up with the reference's arithmetic, so every pixel gets exactly the bits the
//! recursive C++ computed.

use std::ops::{AddAssign, Range};

use crate::bvh::Bvh;
use crate::hit::{Hit, NO_BOUND};
use crate::math::V3;
use crate::rays::{CastStats, EngineError, Ray, RayCaster};
use crate::scene::{MaterialKind, Scene};
use crate::shade::{
    diffuse_colour, fresnel, fresnel_colour, hit_normal, hit_point, mirror_colour, phong_colour,
    reflect, refract, LightTerm, PreparedLight,
};
use crate::spawn::{Departure, SpawnPolicy};
use crate::world::{World, WorldError};

/// Everything tracing needs, prepared once per render.
#[derive(Clone, Debug)]
pub struct PreparedScene {
    pub world: World,
    pub bvh: Bvh,
    pub lights: Vec<PreparedLight>,
    /// Per global triangle: whether shadow rays test it.
    casts_shadow: Vec<bool>,
    pub background: V3,
    pub bias: f32,
    pub max_depth: u32,
    /// How secondary and shadow rays are spawned (the thesis' way unless set).
    pub spawn: SpawnPolicy,
}

impl PreparedScene {
    pub fn new(scene: &Scene) -> Result<PreparedScene, WorldError> {
        let world = World::new(scene)?;
        let bvh = Bvh::build(&world.triangles);
        let casts_shadow = (0..world.triangles.len() as u32)
            .map(|t| world.casts_shadow(t))
            .collect();
        Ok(PreparedScene {
            bvh,
            casts_shadow,
            lights: scene.lights.iter().map(PreparedLight::new).collect(),
            world,
            background: V3::from(scene.options.background),
            bias: scene.options.bias,
            max_depth: scene.options.max_depth,
            spawn: SpawnPolicy::Thesis,
        })
    }

    /// Whether a ray (a shadow ray if `shadow`) is tested against `triangle` (shadow rays
    /// skip objects that cast no shadow).
    pub fn tests(&self, shadow: bool, triangle: u32) -> bool {
        !shadow || self.casts_shadow[triangle as usize]
    }

    /// Per global triangle: whether it casts shadows.
    pub fn casts_shadow(&self) -> &[bool] {
        &self.casts_shadow
    }
}

/// Work counters of a trace.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraceStats {
    pub primary_rays: u64,
    pub reflection_rays: u64,
    pub refraction_rays: u64,
    pub shadow_rays: u64,
    /// What the ray caster did.
    pub cast: CastStats,
}

impl TraceStats {
    pub fn rays(&self) -> u64 {
        self.primary_rays + self.reflection_rays + self.refraction_rays + self.shadow_rays
    }
}

impl AddAssign for TraceStats {
    fn add_assign(&mut self, o: TraceStats) {
        self.primary_rays += o.primary_rays;
        self.reflection_rays += o.reflection_rays;
        self.refraction_rays += o.refraction_rays;
        self.shadow_rays += o.shadow_rays;
        self.cast += o.cast;
    }
}

/// How a castRay node gets its colour once its children are known.
#[derive(Clone, Debug)]
enum Shading {
    /// A miss, a ray deeper than the maximum depth, or (until traced) a pending ray.
    Background,
    Diffuse {
        terms: Range<usize>,
    },
    Phong {
        terms: Range<usize>,
        object: u32,
    },
    Mirror {
        reflection: usize,
    },
    Glass {
        kr: f32,
        refraction: Option<usize>,
        reflection: usize,
    },
}

/// One castRay call.
struct CastNode {
    orig: V3,
    dir: V3,
    /// The spawn policy's window (0 and `None` for primary rays).
    t_min: f32,
    exclude: Option<u32>,
    depth: u32,
    shading: Shading,
}

struct ShadowRay {
    orig: V3,
    dir: V3,
    bound: f32,
    t_min: f32,
    exclude: Option<u32>,
    /// Index into `visible`.
    slot: usize,
}

#[derive(Clone, Copy)]
enum SecondaryKind {
    Reflection,
    Refraction,
}

/// Traces the primary rays `(origin, direction)` and returns one colour per ray: each level
/// of the ray tree (castRay and shadow rays together) is one wavefront for `caster`.
pub fn trace_rays(
    scene: &PreparedScene,
    caster: &dyn RayCaster,
    primary: &[(V3, V3)],
) -> Result<(Vec<V3>, TraceStats), EngineError> {
    let mut tree = RayTree {
        scene,
        nodes: Vec::new(),
        terms: Vec::new(),
        visible: Vec::new(),
        stats: TraceStats::default(),
    };
    let mut level: Vec<usize> = Vec::with_capacity(primary.len());
    for &(orig, dir) in primary {
        level.push(tree.nodes.len());
        tree.nodes.push(CastNode {
            orig,
            dir,
            t_min: 0.0,
            exclude: None,
            depth: 0,
            shading: Shading::Background,
        });
    }
    tree.stats.primary_rays = primary.len() as u64;
    let mut shadows: Vec<ShadowRay> = Vec::new();
    let mut rays: Vec<Ray> = Vec::new();
    let mut found: Vec<Option<Hit>> = Vec::new();

    while !level.is_empty() || !shadows.is_empty() {
        rays.clear();
        rays.extend(level.iter().map(|&n| {
            let node = &tree.nodes[n];
            Ray {
                orig: node.orig,
                dir: node.dir,
                bound: NO_BOUND,
                shadow: false,
                t_min: node.t_min,
                exclude: node.exclude,
            }
        }));
        rays.extend(shadows.iter().map(|s| Ray {
            orig: s.orig,
            dir: s.dir,
            bound: s.bound,
            shadow: true,
            t_min: s.t_min,
            exclude: s.exclude,
        }));
        found.clear();
        found.resize(rays.len(), None);
        tree.stats.cast += caster.cast(&rays, &mut found)?;

        let mut next_level = Vec::new();
        let mut next_shadows = Vec::new();
        for (&n, hit) in level.iter().zip(&found) {
            if let Some(hit) = hit {
                tree.shade_hit(n, hit, &mut next_level, &mut next_shadows);
            }
        }
        for (s, hit) in shadows.iter().zip(&found[level.len()..]) {
            tree.visible[s.slot] = hit.is_none();
        }
        level = next_level;
        shadows = next_shadows;
    }
    Ok((tree.colours(), tree.stats))
}

struct RayTree<'a> {
    scene: &'a PreparedScene,
    nodes: Vec<CastNode>,
    /// Light terms of diffuse and Phong hits, with the slot of their shadow ray's answer.
    terms: Vec<(LightTerm, usize)>,
    visible: Vec<bool>,
    stats: TraceStats,
}

impl RayTree<'_> {
    /// A secondary castRay; deeper than the maximum depth it is the background, untraced.
    fn cast(
        &mut self,
        (orig, dir): (V3, V3),
        departure: &Departure,
        depth: u32,
        kind: SecondaryKind,
        next: &mut Vec<usize>,
    ) -> usize {
        let index = self.nodes.len();
        let (t_min, exclude) = departure.ray(dir);
        self.nodes.push(CastNode {
            orig,
            dir,
            t_min,
            exclude,
            depth,
            shading: Shading::Background,
        });
        if depth <= self.scene.max_depth {
            next.push(index);
            match kind {
                SecondaryKind::Reflection => self.stats.reflection_rays += 1,
                SecondaryKind::Refraction => self.stats.refraction_rays += 1,
            }
        }
        index
    }

    fn shade_hit(
        &mut self,
        n: usize,
        hit: &Hit,
        next: &mut Vec<usize>,
        shadows: &mut Vec<ShadowRay>,
    ) {
        let scene = self.scene;
        let (orig, dir, depth) = (self.nodes[n].orig, self.nodes[n].dir, self.nodes[n].depth);
        let tri = &scene.world.triangles[hit.triangle as usize];
        let material = &scene.world.materials[tri.object as usize];
        let p = hit_point(orig, dir, hit);
        let normal = hit_normal(tri, hit);
        let departure = scene
            .spawn
            .depart(orig, dir, hit.t, hit.triangle, &tri.verts);
        let shading = match material.kind {
            MaterialKind::Diffuse | MaterialKind::Phong => {
                let start = self.terms.len();
                for light in &scene.lights {
                    let il = light.illuminate(p);
                    let term = match material.kind {
                        MaterialKind::Phong => LightTerm::phong(&il, normal, dir, material.n),
                        _ => LightTerm::diffuse(&il, normal),
                    };
                    let slot = self.visible.len();
                    self.visible.push(true);
                    let (t_min, exclude) = departure.ray(-il.dir);
                    shadows.push(ShadowRay {
                        orig: p + normal * scene.bias,
                        dir: -il.dir,
                        bound: il.distance,
                        t_min,
                        exclude,
                        slot,
                    });
                    self.terms.push((term, slot));
                }
                self.stats.shadow_rays += scene.lights.len() as u64;
                let terms = start..self.terms.len();
                if material.kind == MaterialKind::Phong {
                    Shading::Phong {
                        terms,
                        object: tri.object,
                    }
                } else {
                    Shading::Diffuse { terms }
                }
            }
            MaterialKind::Reflection => {
                let r = reflect(dir, normal).normalized();
                let reflection = self.cast(
                    (p + normal * scene.bias, r),
                    &departure,
                    depth + 1,
                    SecondaryKind::Reflection,
                    next,
                );
                Shading::Mirror { reflection }
            }
            MaterialKind::ReflectionRefraction => {
                let kr = fresnel(dir, normal, material.ior);
                let outside = dir.dot(normal) < 0.0;
                let bias = normal * scene.bias;
                let refraction = (kr < 1.0).then(|| {
                    let d = refract(dir, normal, material.ior).normalized();
                    let o = if outside { p - bias } else { p + bias };
                    self.cast(
                        (o, d),
                        &departure,
                        depth + 1,
                        SecondaryKind::Refraction,
                        next,
                    )
                });
                let d = reflect(dir, normal).normalized();
                let o = if outside { p + bias } else { p - bias };
                let reflection = self.cast(
                    (o, d),
                    &departure,
                    depth + 1,
                    SecondaryKind::Reflection,
                    next,
                );
                Shading::Glass {
                    kr,
                    refraction,
                    reflection,
                }
            }
        };
        self.nodes[n].shading = shading;
    }

    /// Colours bottom-up: children always come after their parent.
    fn colours(&self) -> Vec<V3> {
        let mut colour = vec![V3::ZERO; self.nodes.len()];
        for i in (0..self.nodes.len()).rev() {
            let lit = |terms: &Range<usize>| {
                self.terms[terms.clone()]
                    .iter()
                    .map(|&(t, slot)| (t, self.visible[slot]))
            };
            colour[i] = match &self.nodes[i].shading {
                Shading::Background => self.scene.background,
                Shading::Diffuse { terms } => diffuse_colour(lit(terms)),
                Shading::Phong { terms, object } => {
                    let m = &self.scene.world.materials[*object as usize];
                    phong_colour(lit(terms), V3::from(m.albedo), m.kd, m.ks)
                }
                Shading::Mirror { reflection } => mirror_colour(colour[*reflection]),
                Shading::Glass {
                    kr,
                    refraction,
                    reflection,
                } => {
                    let refracted = refraction.map_or(V3::ZERO, |r| colour[r]);
                    fresnel_colour(colour[*reflection], refracted, *kr)
                }
            };
        }
        colour.truncate(self.stats.primary_rays as usize);
        colour
    }
}
