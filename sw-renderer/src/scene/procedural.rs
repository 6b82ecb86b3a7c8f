//! Procedural meshes for the project's scenes: planes, surfaces of revolution (lathe, cylinder,
//! pen), a curved studio backdrop and Newell's Utah teapot. Every generator checks its inputs
//! and returns a [`GeometryError`] saying what was expected instead of panicking.
//!
//! Conventions: y is up. Normals are per triangle corner and point to the outside of closed
//! shapes (to the lit side of open ones); triangles wind counter-clockwise seen from the side
//! the normal points to.

use glam::{Vec2, Vec3};
use thiserror::Error;

use super::Mesh;

/// What was wrong with a generator's parameters.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{0}")]
pub struct GeometryError(pub String);

/// Larger meshes are refused: they would only exhaust memory.
pub const MAX_TRIANGLES: u64 = 4_000_000;

/// Neighbouring profile segments that turn by more than this keep separate normals (a crease,
/// e.g. the rim of a cylinder); gentler turns share an averaged, smooth normal.
pub const CREASE_DEG: f32 = 50.0;

fn finite(name: &str, x: f32) -> Result<f32, GeometryError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(GeometryError(format!(
            "{name} must be a finite number, found {x}"
        )))
    }
}

fn positive(name: &str, x: f32) -> Result<f32, GeometryError> {
    if finite(name, x)? > 0.0 {
        Ok(x)
    } else {
        Err(GeometryError(format!(
            "{name} must be greater than 0, found {x}"
        )))
    }
}

fn non_negative(name: &str, x: f32) -> Result<f32, GeometryError> {
    if finite(name, x)? >= 0.0 {
        Ok(x)
    } else {
        Err(GeometryError(format!(
            "{name} must be 0 or more, found {x}"
        )))
    }
}

fn at_least(name: &str, n: u32, min: u32) -> Result<u32, GeometryError> {
    if n >= min {
        Ok(n)
    } else {
        Err(GeometryError(format!(
            "{name} must be at least {min}, found {n}"
        )))
    }
}

fn check_size(triangles: u64) -> Result<(), GeometryError> {
    if triangles <= MAX_TRIANGLES {
        Ok(())
    } else {
        Err(GeometryError(format!(
            "these parameters make {triangles} triangles, more than the limit of {MAX_TRIANGLES}"
        )))
    }
}

/// A polyline in a 2-D (a, b) plane — (radius, height) for a lathe, (z, y) for an extrusion —
/// with the normals its segments get at each end. The outside is to the right when walking
/// along it: segment direction (da, db) has normal (db, −da).
struct Profile {
    points: Vec<Vec2>,
    /// Per segment k: normals at its start (point k) and at its end (point k+1).
    normals: Vec<[Vec2; 2]>,
}

impl Profile {
    fn new(points: Vec<Vec2>) -> Result<Profile, GeometryError> {
        if points.len() < 2 {
            return Err(GeometryError(format!(
                "a profile needs at least 2 points, found {}",
                points.len()
            )));
        }
        for (k, p) in points.iter().enumerate() {
            finite(&format!("profile point {k}"), p.x)?;
            finite(&format!("profile point {k}"), p.y)?;
        }
        let mut faces = Vec::with_capacity(points.len() - 1);
        for (k, w) in points.windows(2).enumerate() {
            let t = w[1] - w[0];
            if t.length() <= 1e-6 * (w[0].abs().max_element() + w[1].abs().max_element()).max(1e-6)
            {
                return Err(GeometryError(format!(
                    "profile points {k} and {} are the same point ({}, {})",
                    k + 1,
                    w[0].x,
                    w[0].y
                )));
            }
            faces.push(Vec2::new(t.y, -t.x).normalize());
        }
        let cos_crease = CREASE_DEG.to_radians().cos();
        let smooth = |a: Vec2, b: Vec2| {
            if a.dot(b) >= cos_crease {
                (a + b).normalize()
            } else {
                b
            }
        };
        let normals = (0..faces.len())
            .map(|k| {
                let start = if k > 0 {
                    smooth(faces[k - 1], faces[k])
                } else {
                    faces[k]
                };
                let end = if k + 1 < faces.len() {
                    smooth(faces[k + 1], faces[k])
                } else {
                    faces[k]
                };
                [start, end]
            })
            .collect();
        Ok(Profile { points, normals })
    }

    fn segments(&self) -> usize {
        self.points.len() - 1
    }
}

/// A flat rectangle in the y = 0 plane, centred on the origin, normal +y: `width` along x,
/// `depth` along z, split into `segments` = [along x, along z] quads of two triangles.
pub fn plane(width: f32, depth: f32, segments: [u32; 2]) -> Result<Mesh, GeometryError> {
    positive("width", width)?;
    positive("depth", depth)?;
    at_least("segments[0] (along x)", segments[0], 1)?;
    at_least("segments[1] (along z)", segments[1], 1)?;
    let profile = vec![Vec2::new(depth / 2.0, 0.0), Vec2::new(-depth / 2.0, 0.0)];
    extrude(Profile::new(profile)?, width, segments[0], segments[1])
}

/// A surface of revolution: `profile` holds (radius, height) points, revolved about the y axis
/// in `segments` steps. Walk the profile with the outside on the right, e.g. from the bottom
/// centre outwards, up the side and back in to the top centre; points with radius 0 become
/// single pole vertices, so a profile that starts and ends on the axis gives a closed mesh.
pub fn lathe(profile: &[Vec2], segments: u32) -> Result<Mesh, GeometryError> {
    at_least("segments", segments, 3)?;
    let profile = Profile::new(profile.to_vec())?;
    for (k, p) in profile.points.iter().enumerate() {
        non_negative(&format!("the radius of profile point {k}"), p.x)?;
    }
    for (k, w) in profile.points.windows(2).enumerate() {
        if w[0].x == 0.0 && w[1].x == 0.0 {
            return Err(GeometryError(format!(
                "profile points {k} and {} both lie on the axis (radius 0): that segment has no surface",
                k + 1
            )));
        }
    }
    check_size(2 * profile.segments() as u64 * segments as u64)?;
    let cos_crease = CREASE_DEG.to_radians().cos();
    let n = segments as usize;
    let mut grid = Grid::default();
    let rows: Vec<Row> = profile
        .points
        .iter()
        .map(|p| {
            if p.x == 0.0 {
                Row::Pole(grid.vertex(Vec3::new(0.0, p.y, 0.0)))
            } else {
                Row::Ring(
                    (0..n)
                        .map(|j| {
                            let (s, c) = angle(j, n).sin_cos();
                            grid.vertex(Vec3::new(p.x * c, p.y, -p.x * s))
                        })
                        .collect(),
                )
            }
        })
        .collect();
    for k in 0..profile.segments() {
        let [n0, n1] = profile.normals[k];
        for j in 0..n {
            let j1 = (j + 1) % n;
            let corner = |row: usize, col: usize, n2: Vec2| {
                let normal = if profile.points[row].x == 0.0 && n2.y.abs() >= cos_crease {
                    // A smooth pole (sphere-like): the normal there is the axis itself.
                    Vec3::new(0.0, n2.y.signum(), 0.0)
                } else {
                    // A ring, or the apex of a cone: there each column keeps its own normal,
                    // taken at the middle of the column.
                    let a = if profile.points[row].x == 0.0 {
                        angle(2 * j + 1, 2 * n)
                    } else {
                        angle(col, n)
                    };
                    let (s, c) = a.sin_cos();
                    Vec3::new(n2.x * c, n2.y, -n2.x * s).normalize()
                };
                let u = if col == j1 && j1 == 0 {
                    1.0
                } else {
                    col as f32 / n as f32
                };
                let v = row as f32 / profile.segments() as f32;
                (rows[row].index(col), normal, Vec2::new(u, v))
            };
            let a = corner(k, j, n0);
            let b = corner(k, j1, n0);
            let c = corner(k + 1, j1, n1);
            let d = corner(k + 1, j, n1);
            grid.quad(a, b, c, d);
        }
    }
    Ok(grid.mesh)
}

fn angle(j: usize, n: usize) -> f32 {
    std::f32::consts::TAU * j as f32 / n as f32
}

/// A closed cylinder (a frustum when `top_radius` differs from `radius`, a cone when it is 0)
/// standing on y = 0 around the y axis.
pub fn cylinder(
    radius: f32,
    top_radius: f32,
    height: f32,
    segments: u32,
) -> Result<Mesh, GeometryError> {
    positive("radius", radius)?;
    non_negative("top_radius", top_radius)?;
    positive("height", height)?;
    let mut profile = vec![
        Vec2::ZERO,
        Vec2::new(radius, 0.0),
        Vec2::new(top_radius, height),
    ];
    if top_radius > 0.0 {
        profile.push(Vec2::new(0.0, height));
    }
    lathe(&profile, segments)
}

/// A pen along the y axis: a conical tip of `tip_length` with its point at the origin, then a
/// cylindrical body of `length` and `radius`, closed by a flat cap.
pub fn pen(
    radius: f32,
    length: f32,
    tip_length: f32,
    segments: u32,
) -> Result<Mesh, GeometryError> {
    positive("radius", radius)?;
    positive("length", length)?;
    positive("tip_length", tip_length)?;
    let top = tip_length + length;
    lathe(
        &[
            Vec2::ZERO,
            Vec2::new(radius, tip_length),
            Vec2::new(radius, top),
            Vec2::new(0.0, top),
        ],
        segments,
    )
}

/// A studio backdrop: a floor in y = 0 running along z from `depth`/2 back to −`depth`/2, where
/// it bends up into a wall at z = −`depth`/2 that ends at `height`. The bend is a quarter
/// ellipse reaching `radius` along z and `bend_height` up (equal: a quarter circle; both 0: a
/// sharp corner); a `height` below `bend_height` ends the backdrop inside the bend, still
/// leaning back. `width` runs along x, centred. Normals face the open side (up, then +z).
#[derive(Clone, Debug, PartialEq)]
pub struct Backdrop {
    pub width: f32,
    pub depth: f32,
    pub height: f32,
    pub radius: f32,
    pub bend_height: f32,
    pub width_segments: u32,
    pub floor_segments: u32,
    pub bend_segments: u32,
    pub wall_segments: u32,
}

pub fn backdrop(b: &Backdrop) -> Result<Mesh, GeometryError> {
    positive("width", b.width)?;
    positive("depth", b.depth)?;
    positive("height", b.height)?;
    non_negative("radius", b.radius)?;
    non_negative("bend_height", b.bend_height)?;
    if b.radius >= b.depth {
        return Err(GeometryError(format!(
            "radius ({}) must be smaller than depth ({})",
            b.radius, b.depth
        )));
    }
    if (b.radius == 0.0) != (b.bend_height == 0.0) {
        return Err(GeometryError(format!(
            "radius ({}) and bend_height ({}) must both be 0 (a sharp corner) or both be more",
            b.radius, b.bend_height
        )));
    }
    at_least("width_segments", b.width_segments, 1)?;
    let floor_segments = at_least("floor_segments", b.floor_segments, 1)?;
    let bend_segments = if b.radius > 0.0 {
        at_least("bend_segments", b.bend_segments, 1)?
    } else {
        0
    };
    let has_wall = b.height > b.bend_height;
    let wall_segments = if has_wall {
        at_least("wall_segments", b.wall_segments, 1)?
    } else {
        0
    };
    check_size(
        2 * (floor_segments as u64 + wall_segments as u64 + bend_segments as u64)
            * b.width_segments as u64,
    )?;
    let back = -b.depth / 2.0;
    let bend_z = back + b.radius;
    let front = b.depth / 2.0;
    let mut points = Vec::new();
    for i in 0..floor_segments {
        let t = i as f32 / floor_segments as f32;
        points.push(Vec2::new(front + (bend_z - front) * t, 0.0));
    }
    // The ellipse (z, y) = (bend_z − radius·sin φ, bend_height·(1 − cos φ)), up to the height.
    let bend_end = if has_wall {
        std::f32::consts::FRAC_PI_2
    } else {
        (1.0 - b.height / b.bend_height).acos()
    };
    let on_bend = |phi: f32| {
        Vec2::new(
            bend_z - b.radius * phi.sin(),
            b.bend_height * (1.0 - phi.cos()),
        )
    };
    for i in 0..bend_segments {
        points.push(on_bend(bend_end * i as f32 / bend_segments as f32));
    }
    if has_wall {
        for i in 0..=wall_segments {
            let t = i as f32 / wall_segments as f32;
            points.push(Vec2::new(
                back,
                b.bend_height + (b.height - b.bend_height) * t,
            ));
        }
    } else {
        points.push(on_bend(bend_end));
    }
    extrude(Profile::new(points)?, b.width, b.width_segments, 1)
}

/// Sweeps a profile in the (z, y) plane along x over `width`, centred; `across` (≥ 1) columns,
/// and each profile segment split into `along` (≥ 1) rows. Callers check the parameters.
fn extrude(profile: Profile, width: f32, across: u32, along: u32) -> Result<Mesh, GeometryError> {
    check_size(2 * profile.segments() as u64 * across as u64 * along as u64)?;
    let (across, along) = (across as usize, along as usize);
    let rows_total = profile.segments() * along;
    let mut grid = Grid::default();
    // Row r of the grid lies on profile segment r / along at fraction (r % along) / along.
    let row_point = |r: usize| -> Vec2 {
        let k = (r / along).min(profile.segments() - 1);
        let f = (r - k * along) as f32 / along as f32;
        profile.points[k].lerp(profile.points[k + 1], f)
    };
    let x = |i: usize| -width / 2.0 + width * i as f32 / across as f32;
    let rows: Vec<Vec<u32>> = (0..=rows_total)
        .map(|r| {
            let p = row_point(r);
            (0..=across)
                .map(|i| grid.vertex(Vec3::new(x(i), p.y, p.x)))
                .collect()
        })
        .collect();
    for r in 0..rows_total {
        let k = r / along;
        let [n0, n1] = profile.normals[k];
        let f0 = (r - k * along) as f32 / along as f32;
        let f1 = (r + 1 - k * along) as f32 / along as f32;
        let normal = |f: f32| {
            let n = n0.lerp(n1, f).normalize();
            Vec3::new(0.0, n.y, n.x)
        };
        let (top, bottom) = (normal(f0), normal(f1));
        for i in 0..across {
            let corner = |row: usize, col: usize, n: Vec3| {
                (
                    rows[row][col],
                    n,
                    Vec2::new(col as f32 / across as f32, row as f32 / rows_total as f32),
                )
            };
            grid.quad(
                corner(r, i, top),
                corner(r, i + 1, top),
                corner(r + 1, i + 1, bottom),
                corner(r + 1, i, bottom),
            );
        }
    }
    Ok(grid.mesh)
}

/// A row of a swept grid: a ring of vertices, or one vertex on the axis.
enum Row {
    Ring(Vec<u32>),
    Pole(u32),
}

impl Row {
    fn index(&self, col: usize) -> u32 {
        match self {
            Row::Ring(v) => v[col],
            Row::Pole(i) => *i,
        }
    }
}

type Corner = (u32, Vec3, Vec2);

/// Accumulates a mesh from quads (a, b, c, d counter-clockwise seen from outside).
#[derive(Default)]
struct Grid {
    mesh: Mesh,
}

impl Grid {
    fn vertex(&mut self, p: Vec3) -> u32 {
        self.mesh.positions.push(p);
        (self.mesh.positions.len() - 1) as u32
    }

    /// Adds the triangle unless it has no area (a ray could never hit it).
    fn triangle(&mut self, a: Corner, b: Corner, c: Corner) {
        let [pa, pb, pc] = [a.0, b.0, c.0].map(|i| self.mesh.positions[i as usize]);
        if (pb - pa).cross(pc - pa) == Vec3::ZERO {
            return;
        }
        self.mesh.triangles.push([a.0, b.0, c.0]);
        self.mesh.normals.push([a.1, b.1, c.1]);
        self.mesh.uvs.push([a.2, b.2, c.2]);
    }

    /// Where an edge is collapsed (a pole: a and b, or c and d, are one vertex) only the other
    /// triangle has area.
    fn quad(&mut self, a: Corner, b: Corner, c: Corner, d: Corner) {
        self.triangle(a, b, c);
        self.triangle(a, c, d);
    }
}

/// Newell's Utah teapot, y up, spout towards +x, standing on y = 0: its 32 bicubic Bézier patches
/// each cut into `segments`² quads of two triangles, less those without area (along the patch
/// edges collapsed to a point, at the lid's knob and the bottom centre), scaled by `size` (at 1
/// it is 3.15 tall). Normals come from the patch derivatives.
pub fn teapot(segments: u32, size: f32) -> Result<Mesh, GeometryError> {
    at_least("segments", segments, 1)?;
    positive("size", size)?;
    check_size(2 * TEAPOT_PATCHES.len() as u64 * segments as u64 * segments as u64)?;
    let n = segments as usize;
    let mut grid = Grid::default();
    for patch in &TEAPOT_PATCHES {
        let patch = BezierPatch::new(patch);
        let mut corners = Vec::with_capacity((n + 1) * (n + 1));
        for a in 0..=n {
            for b in 0..=n {
                let (u, v) = (a as f64 / n as f64, b as f64 / n as f64);
                let (p, normal) = patch.point_and_normal(u, v);
                let index = grid.vertex(newell_to_y_up(p) * size);
                corners.push((index, newell_to_y_up(normal), Vec2::new(v as f32, u as f32)));
            }
        }
        let at = |a: usize, b: usize| corners[a * (n + 1) + b];
        for a in 0..n {
            for b in 0..n {
                // Where a patch edge collapses to a point (or, coarsely cut, a whole quad to a
                // line) a triangle has no area; `Grid::triangle` leaves those out.
                grid.quad(at(a, b), at(a, b + 1), at(a + 1, b + 1), at(a + 1, b));
            }
        }
    }
    Ok(grid.mesh)
}

/// Newell's data has z up; the thesis' scenes have y up. A rotation, so windings keep their sense.
fn newell_to_y_up(p: glam::DVec3) -> Vec3 {
    Vec3::new(p.x as f32, p.z as f32, -p.y as f32)
}

const EDGE_U0: usize = 0;
const EDGE_U1: usize = 1;
const EDGE_V0: usize = 2;
const EDGE_V1: usize = 3;

/// One bicubic patch: control point (i, j) weighs Bernstein polynomial i of u and j of v.
struct BezierPatch {
    control: [[glam::DVec3; 4]; 4],
    /// Per edge (u = 0, u = 1, v = 0, v = 1): all four control points are the same point.
    collapsed: [bool; 4],
}

impl BezierPatch {
    fn new(indices: &[u16; 16]) -> BezierPatch {
        let control: [[glam::DVec3; 4]; 4] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                glam::Vec3::from_array(TEAPOT_POINTS[indices[4 * i + j] as usize]).as_dvec3()
            })
        });
        let same = |pts: [glam::DVec3; 4]| pts.iter().all(|p| *p == pts[0]);
        let collapsed = [
            same(control[0]),
            same(control[3]),
            same(std::array::from_fn(|i| control[i][0])),
            same(std::array::from_fn(|i| control[i][3])),
        ];
        BezierPatch { control, collapsed }
    }

    fn eval(&self, bu: [f64; 4], bv: [f64; 4]) -> glam::DVec3 {
        let mut sum = glam::DVec3::ZERO;
        for (i, row) in self.control.iter().enumerate() {
            for (j, p) in row.iter().enumerate() {
                sum += *p * (bu[i] * bv[j]);
            }
        }
        sum
    }

    /// The surface point and unit outward normal at (u, v). Where the derivatives vanish (on a
    /// collapsed edge) the normal is taken a little inside the patch, where it is well defined.
    fn point_and_normal(&self, u: f64, v: f64) -> (glam::DVec3, glam::DVec3) {
        let point =
            if (u == 0.0 && self.collapsed[EDGE_U0]) || (v == 0.0 && self.collapsed[EDGE_V0]) {
                self.control[0][0]
            } else if u == 1.0 && self.collapsed[EDGE_U1] || (v == 1.0 && self.collapsed[EDGE_V1]) {
                self.control[3][3]
            } else {
                self.eval(bernstein(u), bernstein(v))
            };
        let (mut nu, mut nv) = (u, v);
        for _ in 0..8 {
            let du = self.eval(bernstein_derivative(nu), bernstein(nv));
            let dv = self.eval(bernstein(nu), bernstein_derivative(nv));
            // Newell's patches run so that ∂P/∂v × ∂P/∂u faces outwards.
            let normal = dv.cross(du);
            if normal.length() > 1e-9 {
                return (point, normal.normalize());
            }
            nu += (0.5 - nu) * 1e-3;
            nv += (0.5 - nv) * 1e-3;
        }
        // Unreachable with the teapot data (only edges collapse, never a whole patch); kept
        // finite so a mesh can never carry a NaN normal.
        (point, glam::DVec3::Y)
    }
}

fn bernstein(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t]
}

fn bernstein_derivative(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [
        -3.0 * s * s,
        3.0 * s * s - 6.0 * t * s,
        6.0 * t * s - 3.0 * t * t,
        3.0 * t * t,
    ]
}

/// The Utah teapot as Martin Newell modelled it in 1975 (public data; 32 patches with the bottom
/// added in later distributions, 306 points, z up), as published in the `teaset` archive of
/// Steve Baker (sjbaker.org/teapot) — there 1-based, here 0-based indices into TEAPOT_POINTS,
/// 16 per patch, row by row.
#[rustfmt::skip]
const TEAPOT_PATCHES: [[u16; 16]; 32] = [
    [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15],
    [3, 16, 17, 18, 7, 19, 20, 21, 11, 22, 23, 24, 15, 25, 26, 27],
    [18, 28, 29, 30, 21, 31, 32, 33, 24, 34, 35, 36, 27, 37, 38, 39],
    [30, 40, 41, 0, 33, 42, 43, 4, 36, 44, 45, 8, 39, 46, 47, 12],
    [12, 13, 14, 15, 48, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59],
    [15, 25, 26, 27, 51, 60, 61, 62, 55, 63, 64, 65, 59, 66, 67, 68],
    [27, 37, 38, 39, 62, 69, 70, 71, 65, 72, 73, 74, 68, 75, 76, 77],
    [39, 46, 47, 12, 71, 78, 79, 48, 74, 80, 81, 52, 77, 82, 83, 56],
    [56, 57, 58, 59, 84, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95],
    [59, 66, 67, 68, 87, 96, 97, 98, 91, 99, 100, 101, 95, 102, 103, 104],
    [68, 75, 76, 77, 98, 105, 106, 107, 101, 108, 109, 110, 104, 111, 112, 113],
    [77, 82, 83, 56, 107, 114, 115, 84, 110, 116, 117, 88, 113, 118, 119, 92],
    [120, 121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135],
    [123, 136, 137, 120, 127, 138, 139, 124, 131, 140, 141, 128, 135, 142, 143, 132],
    [132, 133, 134, 135, 144, 145, 146, 147, 148, 149, 150, 151, 68, 152, 153, 154],
    [135, 142, 143, 132, 147, 155, 156, 144, 151, 157, 158, 148, 154, 159, 160, 68],
    [161, 162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176],
    [164, 177, 178, 161, 168, 179, 180, 165, 172, 181, 182, 169, 176, 183, 184, 173],
    [173, 174, 175, 176, 185, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196],
    [176, 183, 184, 173, 188, 197, 198, 185, 192, 199, 200, 189, 196, 201, 202, 193],
    [203, 203, 203, 203, 206, 207, 208, 209, 210, 210, 210, 210, 211, 212, 213, 214],
    [203, 203, 203, 203, 209, 216, 217, 218, 210, 210, 210, 210, 214, 219, 220, 221],
    [203, 203, 203, 203, 218, 223, 224, 225, 210, 210, 210, 210, 221, 226, 227, 228],
    [203, 203, 203, 203, 225, 229, 230, 206, 210, 210, 210, 210, 228, 231, 232, 211],
    [211, 212, 213, 214, 233, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244],
    [214, 219, 220, 221, 236, 245, 246, 247, 240, 248, 249, 250, 244, 251, 252, 253],
    [221, 226, 227, 228, 247, 254, 255, 256, 250, 257, 258, 259, 253, 260, 261, 262],
    [228, 231, 232, 211, 256, 263, 264, 233, 259, 265, 266, 237, 262, 267, 268, 241],
    [269, 269, 269, 269, 278, 279, 280, 281, 274, 275, 276, 277, 270, 271, 272, 273],
    [269, 269, 269, 269, 281, 288, 289, 290, 277, 285, 286, 287, 273, 282, 283, 284],
    [269, 269, 269, 269, 290, 297, 298, 299, 287, 294, 295, 296, 284, 291, 292, 293],
    [269, 269, 269, 269, 299, 304, 305, 278, 296, 302, 303, 274, 293, 300, 301, 270],
];

#[rustfmt::skip]
const TEAPOT_POINTS: [[f32; 3]; 306] = [
    [1.4, 0.0, 2.4], [1.4, -0.784, 2.4], [0.784, -1.4, 2.4], [0.0, -1.4, 2.4],
    [1.3375, 0.0, 2.53125], [1.3375, -0.749, 2.53125], [0.749, -1.3375, 2.53125],
    [0.0, -1.3375, 2.53125], [1.4375, 0.0, 2.53125], [1.4375, -0.805, 2.53125],
    [0.805, -1.4375, 2.53125], [0.0, -1.4375, 2.53125], [1.5, 0.0, 2.4], [1.5, -0.84, 2.4],
    [0.84, -1.5, 2.4], [0.0, -1.5, 2.4], [-0.784, -1.4, 2.4], [-1.4, -0.784, 2.4], [-1.4, 0.0, 2.4],
    [-0.749, -1.3375, 2.53125], [-1.3375, -0.749, 2.53125], [-1.3375, 0.0, 2.53125],
    [-0.805, -1.4375, 2.53125], [-1.4375, -0.805, 2.53125], [-1.4375, 0.0, 2.53125],
    [-0.84, -1.5, 2.4], [-1.5, -0.84, 2.4], [-1.5, 0.0, 2.4], [-1.4, 0.784, 2.4],
    [-0.784, 1.4, 2.4], [0.0, 1.4, 2.4], [-1.3375, 0.749, 2.53125], [-0.749, 1.3375, 2.53125],
    [0.0, 1.3375, 2.53125], [-1.4375, 0.805, 2.53125], [-0.805, 1.4375, 2.53125],
    [0.0, 1.4375, 2.53125], [-1.5, 0.84, 2.4], [-0.84, 1.5, 2.4], [0.0, 1.5, 2.4],
    [0.784, 1.4, 2.4], [1.4, 0.784, 2.4], [0.749, 1.3375, 2.53125], [1.3375, 0.749, 2.53125],
    [0.805, 1.4375, 2.53125], [1.4375, 0.805, 2.53125], [0.84, 1.5, 2.4], [1.5, 0.84, 2.4],
    [1.75, 0.0, 1.875], [1.75, -0.98, 1.875], [0.98, -1.75, 1.875], [0.0, -1.75, 1.875],
    [2.0, 0.0, 1.35], [2.0, -1.12, 1.35], [1.12, -2.0, 1.35], [0.0, -2.0, 1.35], [2.0, 0.0, 0.9],
    [2.0, -1.12, 0.9], [1.12, -2.0, 0.9], [0.0, -2.0, 0.9], [-0.98, -1.75, 1.875],
    [-1.75, -0.98, 1.875], [-1.75, 0.0, 1.875], [-1.12, -2.0, 1.35], [-2.0, -1.12, 1.35],
    [-2.0, 0.0, 1.35], [-1.12, -2.0, 0.9], [-2.0, -1.12, 0.9], [-2.0, 0.0, 0.9],
    [-1.75, 0.98, 1.875], [-0.98, 1.75, 1.875], [0.0, 1.75, 1.875], [-2.0, 1.12, 1.35],
    [-1.12, 2.0, 1.35], [0.0, 2.0, 1.35], [-2.0, 1.12, 0.9], [-1.12, 2.0, 0.9], [0.0, 2.0, 0.9],
    [0.98, 1.75, 1.875], [1.75, 0.98, 1.875], [1.12, 2.0, 1.35], [2.0, 1.12, 1.35],
    [1.12, 2.0, 0.9], [2.0, 1.12, 0.9], [2.0, 0.0, 0.45], [2.0, -1.12, 0.45], [1.12, -2.0, 0.45],
    [0.0, -2.0, 0.45], [1.5, 0.0, 0.225], [1.5, -0.84, 0.225], [0.84, -1.5, 0.225],
    [0.0, -1.5, 0.225], [1.5, 0.0, 0.15], [1.5, -0.84, 0.15], [0.84, -1.5, 0.15], [0.0, -1.5, 0.15],
    [-1.12, -2.0, 0.45], [-2.0, -1.12, 0.45], [-2.0, 0.0, 0.45], [-0.84, -1.5, 0.225],
    [-1.5, -0.84, 0.225], [-1.5, 0.0, 0.225], [-0.84, -1.5, 0.15], [-1.5, -0.84, 0.15],
    [-1.5, 0.0, 0.15], [-2.0, 1.12, 0.45], [-1.12, 2.0, 0.45], [0.0, 2.0, 0.45],
    [-1.5, 0.84, 0.225], [-0.84, 1.5, 0.225], [0.0, 1.5, 0.225], [-1.5, 0.84, 0.15],
    [-0.84, 1.5, 0.15], [0.0, 1.5, 0.15], [1.12, 2.0, 0.45], [2.0, 1.12, 0.45], [0.84, 1.5, 0.225],
    [1.5, 0.84, 0.225], [0.84, 1.5, 0.15], [1.5, 0.84, 0.15], [-1.6, 0.0, 2.025],
    [-1.6, -0.3, 2.025], [-1.5, -0.3, 2.25], [-1.5, 0.0, 2.25], [-2.3, 0.0, 2.025],
    [-2.3, -0.3, 2.025], [-2.5, -0.3, 2.25], [-2.5, 0.0, 2.25], [-2.7, 0.0, 2.025],
    [-2.7, -0.3, 2.025], [-3.0, -0.3, 2.25], [-3.0, 0.0, 2.25], [-2.7, 0.0, 1.8], [-2.7, -0.3, 1.8],
    [-3.0, -0.3, 1.8], [-3.0, 0.0, 1.8], [-1.5, 0.3, 2.25], [-1.6, 0.3, 2.025], [-2.5, 0.3, 2.25],
    [-2.3, 0.3, 2.025], [-3.0, 0.3, 2.25], [-2.7, 0.3, 2.025], [-3.0, 0.3, 1.8], [-2.7, 0.3, 1.8],
    [-2.7, 0.0, 1.575], [-2.7, -0.3, 1.575], [-3.0, -0.3, 1.35], [-3.0, 0.0, 1.35],
    [-2.5, 0.0, 1.125], [-2.5, -0.3, 1.125], [-2.65, -0.3, 0.9375], [-2.65, 0.0, 0.9375],
    [-2.0, -0.3, 0.9], [-1.9, -0.3, 0.6], [-1.9, 0.0, 0.6], [-3.0, 0.3, 1.35], [-2.7, 0.3, 1.575],
    [-2.65, 0.3, 0.9375], [-2.5, 0.3, 1.125], [-1.9, 0.3, 0.6], [-2.0, 0.3, 0.9], [1.7, 0.0, 1.425],
    [1.7, -0.66, 1.425], [1.7, -0.66, 0.6], [1.7, 0.0, 0.6], [2.6, 0.0, 1.425], [2.6, -0.66, 1.425],
    [3.1, -0.66, 0.825], [3.1, 0.0, 0.825], [2.3, 0.0, 2.1], [2.3, -0.25, 2.1], [2.4, -0.25, 2.025],
    [2.4, 0.0, 2.025], [2.7, 0.0, 2.4], [2.7, -0.25, 2.4], [3.3, -0.25, 2.4], [3.3, 0.0, 2.4],
    [1.7, 0.66, 0.6], [1.7, 0.66, 1.425], [3.1, 0.66, 0.825], [2.6, 0.66, 1.425],
    [2.4, 0.25, 2.025], [2.3, 0.25, 2.1], [3.3, 0.25, 2.4], [2.7, 0.25, 2.4], [2.8, 0.0, 2.475],
    [2.8, -0.25, 2.475], [3.525, -0.25, 2.49375], [3.525, 0.0, 2.49375], [2.9, 0.0, 2.475],
    [2.9, -0.15, 2.475], [3.45, -0.15, 2.5125], [3.45, 0.0, 2.5125], [2.8, 0.0, 2.4],
    [2.8, -0.15, 2.4], [3.2, -0.15, 2.4], [3.2, 0.0, 2.4], [3.525, 0.25, 2.49375],
    [2.8, 0.25, 2.475], [3.45, 0.15, 2.5125], [2.9, 0.15, 2.475], [3.2, 0.15, 2.4],
    [2.8, 0.15, 2.4], [0.0, 0.0, 3.15], [0.0, -0.002, 3.15], [0.002, 0.0, 3.15], [0.8, 0.0, 3.15],
    [0.8, -0.45, 3.15], [0.45, -0.8, 3.15], [0.0, -0.8, 3.15], [0.0, 0.0, 2.85], [0.2, 0.0, 2.7],
    [0.2, -0.112, 2.7], [0.112, -0.2, 2.7], [0.0, -0.2, 2.7], [-0.002, 0.0, 3.15],
    [-0.45, -0.8, 3.15], [-0.8, -0.45, 3.15], [-0.8, 0.0, 3.15], [-0.112, -0.2, 2.7],
    [-0.2, -0.112, 2.7], [-0.2, 0.0, 2.7], [0.0, 0.002, 3.15], [-0.8, 0.45, 3.15],
    [-0.45, 0.8, 3.15], [0.0, 0.8, 3.15], [-0.2, 0.112, 2.7], [-0.112, 0.2, 2.7], [0.0, 0.2, 2.7],
    [0.45, 0.8, 3.15], [0.8, 0.45, 3.15], [0.112, 0.2, 2.7], [0.2, 0.112, 2.7], [0.4, 0.0, 2.55],
    [0.4, -0.224, 2.55], [0.224, -0.4, 2.55], [0.0, -0.4, 2.55], [1.3, 0.0, 2.55],
    [1.3, -0.728, 2.55], [0.728, -1.3, 2.55], [0.0, -1.3, 2.55], [1.3, 0.0, 2.4],
    [1.3, -0.728, 2.4], [0.728, -1.3, 2.4], [0.0, -1.3, 2.4], [-0.224, -0.4, 2.55],
    [-0.4, -0.224, 2.55], [-0.4, 0.0, 2.55], [-0.728, -1.3, 2.55], [-1.3, -0.728, 2.55],
    [-1.3, 0.0, 2.55], [-0.728, -1.3, 2.4], [-1.3, -0.728, 2.4], [-1.3, 0.0, 2.4],
    [-0.4, 0.224, 2.55], [-0.224, 0.4, 2.55], [0.0, 0.4, 2.55], [-1.3, 0.728, 2.55],
    [-0.728, 1.3, 2.55], [0.0, 1.3, 2.55], [-1.3, 0.728, 2.4], [-0.728, 1.3, 2.4], [0.0, 1.3, 2.4],
    [0.224, 0.4, 2.55], [0.4, 0.224, 2.55], [0.728, 1.3, 2.55], [1.3, 0.728, 2.55],
    [0.728, 1.3, 2.4], [1.3, 0.728, 2.4], [0.0, 0.0, 0.0], [1.5, 0.0, 0.15], [1.5, 0.84, 0.15],
    [0.84, 1.5, 0.15], [0.0, 1.5, 0.15], [1.5, 0.0, 0.075], [1.5, 0.84, 0.075], [0.84, 1.5, 0.075],
    [0.0, 1.5, 0.075], [1.425, 0.0, 0.0], [1.425, 0.798, 0.0], [0.798, 1.425, 0.0],
    [0.0, 1.425, 0.0], [-0.84, 1.5, 0.15], [-1.5, 0.84, 0.15], [-1.5, 0.0, 0.15],
    [-0.84, 1.5, 0.075], [-1.5, 0.84, 0.075], [-1.5, 0.0, 0.075], [-0.798, 1.425, 0.0],
    [-1.425, 0.798, 0.0], [-1.425, 0.0, 0.0], [-1.5, -0.84, 0.15], [-0.84, -1.5, 0.15],
    [0.0, -1.5, 0.15], [-1.5, -0.84, 0.075], [-0.84, -1.5, 0.075], [0.0, -1.5, 0.075],
    [-1.425, -0.798, 0.0], [-0.798, -1.425, 0.0], [0.0, -1.425, 0.0], [0.84, -1.5, 0.15],
    [1.5, -0.84, 0.15], [0.84, -1.5, 0.075], [1.5, -0.84, 0.075], [0.798, -1.425, 0.0],
    [1.425, -0.798, 0.0],
];
