#pragma once

#include <string>
#include <string_view>

#include "common/scene/mesh_model.h"
#include "common/scene/scene_budget.h"

namespace glint {

// An imported mesh (glTF, PLY) as it travels to a server in place of its
// files: the MeshModel's arrays, bit for bit, so that the server's scene is
// the client's. Little-endian:
//   "GLINTMSH" u32 version (4)
//   u32 textures,  each: u32 width, u32 height, u8 filter, u8 wrap along u,
//                        u8 wrap along v, width*height*3 texels,
//                        u8 has uv transform, then f32 m[4] (columns) offset[2]
//   u32 materials, each: u32 name length, name, f32 color[3], i32 texture,
//                        f32 emission[3], i32 emission texture,
//                        f32 ambient diffuse specular shininess reflectivity
//                        roughness transparency ior, u8 raytrace
//   u32 meshes,    each: u32 material, u32 vertices, u8 has normals, u8 has uvs,
//                        u8 has colours, f32 positions[3v], normals[3v], uvs[2v],
//                        colors[3v], u32 indices, u32[indices]
//   u8 has camera, then f32 eye[3] look_at[3] up[3] fov_y
//   u32 lights,    each: u8 LightType (point, spot, directional), f32 position[3]
//                        direction[3] color[3] attenuation[3] cos_inner cos_outer
std::string encodeMeshBlob(const MeshModel& model);

// Reads a blob, checking every count against the bytes that are there before
// allocating, every index against what it indexes, and charging the budget
// (texels, vertices, triangles); throws InputError starting with `place`.
MeshModel decodeMeshBlob(std::string_view bytes, const std::string& place, SceneBudget& budget);

}  // namespace glint
