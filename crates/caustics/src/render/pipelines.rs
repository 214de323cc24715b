//! The pipelines of the eye render (`--technique none`), built once per run.

use anyhow::Result;
use vkcore::{Context, Cull, Pipeline, ShaderCompiler};

pub use crate::gpu::formats::{COLOR, DEPTH, DISTANCE};
use crate::gpu::mesh_pipeline::{mesh_pipeline, MeshPass};

pub struct EyePipelines {
    pub shadow_map: Pipeline,
    pub background: Pipeline,
    pub back_faces: Pipeline,
    pub front_faces: Pipeline,
    pub composite: Pipeline,
    pub receiver_map: Pipeline,
}

impl EyePipelines {
    pub fn new(ctx: &Context, sh: &ShaderCompiler) -> Result<EyePipelines> {
        let eye =
            |name, frag, colors, cull| MeshPass { name, vert: "eye/mesh.vert", vert_defines: &[], frag, colors, cull };
        Ok(EyePipelines {
            shadow_map: mesh_pipeline(
                ctx,
                sh,
                MeshPass {
                    name: "shadow_map",
                    vert: "shadow/shadow_map.vert",
                    vert_defines: &[],
                    frag: "shadow/shadow_map.frag",
                    colors: vec![DISTANCE],
                    cull: Cull::None,
                },
            )?,
            background: mesh_pipeline(
                ctx,
                sh,
                eye("background", "eye/background.frag", vec![COLOR, COLOR, COLOR, COLOR], Cull::None),
            )?,
            back_faces: mesh_pipeline(
                ctx,
                sh,
                eye("refractor_back_faces", "eye/back_faces.frag", vec![COLOR], Cull::Front),
            )?,
            front_faces: mesh_pipeline(
                ctx,
                sh,
                eye("refractor_front_faces", "eye/front_faces.frag", vec![COLOR], Cull::Back),
            )?,
            composite: Pipeline::compute(ctx, "composite", &sh.compile("eye/composite.comp", &[])?)?,
            receiver_map: Pipeline::compute(ctx, "receiver_map", &sh.compile("receiver/receiver_map.comp", &[])?)?,
        })
    }
}
