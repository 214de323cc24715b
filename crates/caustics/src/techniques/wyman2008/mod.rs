//! Wyman 2008, "Hierarchical caustic maps" (technique `hcm`): a mipmap over the photon buffer
//! records which subtrees hold valid photons ([`pyramid`], Sec. 3.1); a breadth-first traversal
//! from its 16² level down to the photon buffer discards empty subtrees ([`traversal`]), so only
//! valid photons reach the splat ([`splat`]). Converging photons (every photon below a node
//! lands in one caustic-map texel) can be clustered into one photon with their summed power
//! (Sec. 3.2). Splat sizes may vary with the photons' neighbours, in one map or a
//! multi-resolution map (Sec. 3.3); [`thin_lens`] and [`interpolated`] are Fig. 7's thin-lens
//! and multiple-splat-size baselines. Sec. 4's faster photon fetch is [`photon_copy`]'s
//! counterpart, the instanced fetch of `techniques::shared`.
//!
//! Shaders: `shaders_glsl/wyman2008/`.

pub(crate) mod entry;
pub mod interpolated;
pub mod photon_copy;
pub mod push;
mod pyramid;
pub mod settings;
mod splat;
pub mod splat_footprints;
pub mod thin_lens;
mod traversal;

pub use entry::{pack_entry, unpack_entry, ENTRY_BYTES, MAX_SIDE};
pub use pyramid::levels;
pub use settings::{Cluster, SplatMode, VaryingRadius, DUMPS, PAPER};
pub use traversal::{list_records, LIST_CHANNELS};

use crate::gpu::Target;
use crate::techniques::shared::pipelines::point_splat_desc;
use crate::techniques::shared::settings::TraversalPath;
use crate::techniques::shared::targets::COLOR;
use anyhow::Result;
use pyramid::Pyramid;
use vkcore::{
    Buffer, CompactStream, CompactionPath, Context, Finalize, Format, GraphicsDesc, Image, ImageDesc, Memory, Pipeline,
    ShaderCompiler, Topology, VertexAttribute, VertexLayout, ViewKind,
};

/// The traversal's lists as vertex buffers: one packed entry (`entry.rs`) per vertex.
pub(crate) fn entry_layout() -> VertexLayout {
    VertexLayout {
        stride: ENTRY_BYTES as u32,
        attributes: vec![VertexAttribute { location: 0, format: Format::R32_UINT, offset: 0 }],
    }
}

/// The traversal starts at a 16² level (Sec. 3.1: "to avoid processing mipmaps containing only
/// a handful of photons").
pub const TOP_SIDE: u32 = 16;

pub struct Hierarchy {
    path: CompactionPath,
    cluster: Cluster,
    /// Photon buffer side N, padded side P and levels L.
    n: u32,
    padded: u32,
    levels: u32,
    pyramid: Pyramid,
    /// Stands in for the children of level 1 (read from the photon buffer instead).
    dummy: Target,
    /// The TOP_SIDE² entries of level L.
    seed: CompactStream,
    /// lists[k]: the entries after the step at level k+1 (level-k nodes plus finished clusters).
    lists: Vec<CompactStream>,
    /// Per light, the u32 counter of lists[0..L] (bytes on the xfb path).
    counts: Buffer,
    lights: u32,
    build: Pipeline,
    traverse: Pipeline,
    finalize: Option<Finalize>,
    splat: Pipeline,
}

impl Hierarchy {
    pub fn new(
        ctx: &Context,
        sh: &ShaderCompiler,
        n: u32,
        lights: u32,
        traversal: TraversalPath,
        cluster: Cluster,
    ) -> Result<Hierarchy> {
        ctx.require(&format!("technique `hcm` with --path {traversal}"), traversal.features())?;
        let path = traversal.compaction();
        let (padded, levels) = levels(n);
        if padded > MAX_SIDE {
            return Err(crate::input_error!(
                "caustics.photons: the hierarchy's packed entries address photon buffers up to {MAX_SIDE}², not {n}²"
            )
            .into());
        }
        let image = |name: &str| Image::new(ctx, ImageDesc::new_2d(name, COLOR, padded / 2, padded / 2).mips(levels));
        let (power, position, texels) =
            (image("hierarchy power")?, image("hierarchy position")?, image("hierarchy texels")?);
        let view = |i: &Image, m: std::ops::Range<u32>| i.view(ViewKind::D2, m, 0..1);
        let all = [view(&power, 0..levels)?, view(&position, 0..levels)?, view(&texels, 0..levels)?];
        let mips = (0..levels)
            .map(|m| Ok([view(&power, m..m + 1)?, view(&position, m..m + 1)?, view(&texels, m..m + 1)?]))
            .collect::<Result<Vec<_>>>()?;
        let seed_entries: Vec<u32> =
            (0..TOP_SIDE * TOP_SIDE).map(|i| pack_entry([i % TOP_SIDE, i / TOP_SIDE, levels, 0])).collect();
        let stream =
            |name: &str, capacity: u32| CompactStream::with_element_bytes(ctx, name, path, capacity, ENTRY_BYTES);
        let seed = stream("hierarchy seed", seed_entries.len() as u32)?;
        ctx.upload_buffer(seed.data(), bytemuck::cast_slice(&seed_entries))?;
        seed.upload_seeded_counter(ctx, seed_entries.len() as u32)?;
        // List k holds level-k nodes and clusters finished above level k, each covering at least
        // one level-k node with photons: no more entries than level-k nodes over the N² photons.
        let capacity = |k: u32| n.div_ceil(1 << k) * n.div_ceil(1 << k);
        let bytes = capacity(0) as u64 * ENTRY_BYTES;
        let xfb_limit = ctx.info().max_transform_feedback_buffer_size;
        if path == CompactionPath::TransformFeedback && bytes > xfb_limit {
            return Err(crate::input_error!(
                "caustics.photons: the xfb traversal's last list of {n}² photons needs {bytes} bytes of \
                 transform-feedback buffer, more than this device's maxTransformFeedbackBufferSize ({xfb_limit}); \
                 use fewer photons or the compute traversal (--path compute)"
            )
            .into());
        }
        let lists = (0..levels)
            .map(|k| stream(&format!("hierarchy level {k}"), capacity(k)))
            .collect::<vkcore::Result<Vec<_>>>()?;
        let counts = Buffer::new(ctx, "hierarchy counts", (lights.max(1) * levels) as u64 * 4, Memory::Gpu)?;
        let dummy = Target::new(ctx, ImageDesc::new_2d("hierarchy dummy", COLOR, 1, 1))?;

        let build = Pipeline::compute(ctx, "hierarchy.build", &sh.compile("wyman2008/build.comp", &[])?)?;
        let entries = entry_layout();
        let (traverse, finalize) = match path {
            CompactionPath::TransformFeedback => {
                let mut d = GraphicsDesc::new("hierarchy.traverse", sh.compile("wyman2008/traverse.vert", &[])?, None);
                d.geometry = Some(sh.compile("wyman2008/traverse.geom", &[])?);
                d.topology = Topology::Points;
                d.rasterizer_discard = true;
                d.vertex_layout = Some(entries.clone());
                (Pipeline::graphics(ctx, &d)?, None)
            }
            CompactionPath::Compute => {
                let traverse =
                    Pipeline::compute(ctx, "hierarchy.traverse", &sh.compile("wyman2008/traverse.comp", &[])?)?;
                let finalize = Finalize::new(ctx, sh, "hierarchy.finalize")?;
                (traverse, Some(finalize))
            }
        };
        // The point splat, fed the final list's entries instead of photon indices.
        let mut splat = point_splat_desc(sh)?;
        splat.name = "splat_hierarchy".into();
        splat.vertex = sh.compile("shared/splat.vert", &[("HIERARCHY", "1")])?;
        splat.vertex_layout = Some(entries);
        Ok(Hierarchy {
            path,
            cluster,
            n,
            padded,
            levels,
            pyramid: Pyramid { power, position, texels, all, mips },
            dummy,
            seed,
            lists,
            counts,
            lights,
            build,
            traverse,
            finalize,
            splat: Pipeline::graphics(ctx, &splat)?,
        })
    }

    /// The traversal's stream-compaction path.
    pub fn path(&self) -> CompactionPath {
        self.path
    }

    /// Which levels test converging photons for clustering (Sec. 3.2).
    pub fn cluster(&self) -> Cluster {
        self.cluster
    }

    /// The photon buffer's side N.
    pub fn n(&self) -> u32 {
        self.n
    }

    /// The side P the photon buffer is padded to (a power of two, at least N).
    pub fn padded(&self) -> u32 {
        self.padded
    }

    /// The hierarchy's levels L above the photon buffer.
    pub fn levels(&self) -> u32 {
        self.levels
    }

    /// The final list, as the compute splat reads it (packed entries, Sec. 3.1).
    pub fn splat_list(&self) -> crate::techniques::shared::SplatList {
        let kind = crate::techniques::shared::ListKind::HierarchyEntries;
        crate::techniques::shared::SplatList { kind, path: self.path, element_bytes: ENTRY_BYTES }
    }
}
