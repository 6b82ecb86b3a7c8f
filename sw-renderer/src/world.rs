//! World-space geometry, prepared once per render as the reference's `TriangleMesh`
//! constructor did: vertices by object-to-world (with the w divide), corner normals by the
//! transpose of the inverse of object-to-world as directions, then normalised.
//!
//! All triangles of all objects form one flat list in global order (objects in scene order,
//! triangles in mesh order); the global index is the tie-break order between equally near hits.

use thiserror::Error;

use crate::math::{inverse, mult_dir, mult_point, transpose, V3};
use crate::scene::{Material, MaterialKind, Scene};

#[derive(Debug, Error)]
pub enum WorldError {
    #[error("object `{object}`: triangle {triangle} uses vertex {index}, but the mesh has {count} vertices")]
    VertexIndex {
        object: String,
        triangle: usize,
        index: u32,
        count: usize,
    },
    #[error("object `{object}`: {triangles} triangles but {normals} corner-normal triples")]
    NormalCount {
        object: String,
        triangles: usize,
        normals: usize,
    },
    #[error("the scene has {0} triangles; at most 2^32 - 1 are supported")]
    TooManyTriangles(usize),
}

/// One triangle in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldTriangle {
    pub verts: [V3; 3],
    /// Corner normals, transformed and normalised.
    pub normals: [V3; 3],
    /// Index into [`World::materials`] (= the object's index in the scene).
    pub object: u32,
}

#[derive(Clone, Debug)]
pub struct World {
    pub triangles: Vec<WorldTriangle>,
    /// One material per scene object.
    pub materials: Vec<Material>,
}

impl World {
    pub fn new(scene: &Scene) -> Result<World, WorldError> {
        let total = scene.triangle_count();
        if u32::try_from(total).is_err() {
            return Err(WorldError::TooManyTriangles(total));
        }
        let mut triangles = Vec::with_capacity(total);
        for (object_index, object) in scene.objects.iter().enumerate() {
            let mesh = &object.mesh;
            if mesh.normals.len() != mesh.triangles.len() {
                return Err(WorldError::NormalCount {
                    object: object.name.clone(),
                    triangles: mesh.triangles.len(),
                    normals: mesh.normals.len(),
                });
            }
            let o2w = &object.object_to_world;
            let normal_matrix = transpose(&inverse(o2w));
            let positions: Vec<V3> = mesh
                .positions
                .iter()
                .map(|p| mult_point(o2w, V3::from(*p)))
                .collect();
            for (t, (tri, normals)) in mesh.triangles.iter().zip(&mesh.normals).enumerate() {
                let vertex = |index: u32| {
                    positions
                        .get(index as usize)
                        .copied()
                        .ok_or_else(|| WorldError::VertexIndex {
                            object: object.name.clone(),
                            triangle: t,
                            index,
                            count: positions.len(),
                        })
                };
                let normal = |n: glam::Vec3| mult_dir(&normal_matrix, V3::from(n)).normalized();
                triangles.push(WorldTriangle {
                    verts: [vertex(tri[0])?, vertex(tri[1])?, vertex(tri[2])?],
                    normals: [normal(normals[0]), normal(normals[1]), normal(normals[2])],
                    object: object_index as u32,
                });
            }
        }
        let materials = scene.objects.iter().map(|o| o.material.clone()).collect();
        Ok(World {
            triangles,
            materials,
        })
    }

    /// Shadow rays ignore objects of type reflection+refraction (the reference's `kShadowRay`).
    pub fn casts_shadow(&self, triangle: u32) -> bool {
        let object = self.triangles[triangle as usize].object as usize;
        self.materials[object].kind != MaterialKind::ReflectionRefraction
    }
}
