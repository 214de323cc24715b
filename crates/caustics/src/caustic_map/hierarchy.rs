//! Hierarchical caustic maps (Wyman 2008 Sec. 3.1-3.2): a mipmap over the photon buffer records
//! which subtrees hold valid photons (and what the convergence test needs); a breadth-first
//! traversal from its 16² level down to the photon buffer discards empty subtrees, so only
//! valid photons reach the splat. Converging photons (every photon below a node lands in one
//! caustic-map texel) can be clustered into one photon with their summed power.
//!
//! Two traversal paths that produce the same photons (in different orders):
//! - `xfb`: a geometry shader per level emits the children into transform-feedback buffers; the
//!   next level is drawn with vkCmdDrawIndirectByteCountEXT from this level's counter buffer;
//! - `compute`: a compute kernel per level appends with an atomic counter; the next level is
//!   dispatched indirectly.
//!
//! Nothing is read back on the CPU between levels. Shaders: `shaders_glsl/hierarchy/`.

use super::targets::{PhotonTargets, COLOR};
use crate::image_io::{ImageF32, Layer};
use crate::render::gpu::ObjectConstants;
use crate::render::targets::Target;
use anyhow::Result;
use vkcore::{
    Access, Bind, BindingKind as K, Blend, Buffer, CompactStream, CompactionPath, Context, Feature, Format, Frame,
    GraphicsDesc, Image, ImageDesc, ImageView, Memory, Pipeline, Sampler, ShaderCompiler, Targets, Topology, Use,
    VertexAttribute, VertexLayout, ViewKind,
};

/// The traversal starts at a 16² level (Sec. 3.1: "to avoid processing mipmaps containing only
/// a handful of photons").
pub const TOP_SIDE: u32 = 16;
/// Bytes of a list entry: (x, y, level, final) packed into a u32 (`hierarchy/entry.glsl`).
pub const ENTRY_BYTES: u64 = 4;
/// Bit offsets of y, level and final in a packed entry (x in bits 0-11), as in `entry.glsl`.
const ENTRY_Y_SHIFT: u32 = 12;
const ENTRY_LEVEL_SHIFT: u32 = 24;
const ENTRY_FINAL_SHIFT: u32 = 28;
/// The largest padded photon buffer side a packed entry can address (12 bits of x and y).
pub const MAX_SIDE: u32 = 1 << ENTRY_Y_SHIFT;

/// (x, y, level, final) packed as `pack_entry` in `shaders_glsl/hierarchy/entry.glsl` does.
pub fn pack_entry(e: [u32; 4]) -> u32 {
    e[0] | (e[1] << ENTRY_Y_SHIFT) | (e[2] << ENTRY_LEVEL_SHIFT) | (e[3] << ENTRY_FINAL_SHIFT)
}

/// The (x, y, level, final) of a packed entry.
pub fn unpack_entry(p: u32) -> [u32; 4] {
    [p & 0xFFF, (p >> ENTRY_Y_SHIFT) & 0xFFF, (p >> ENTRY_LEVEL_SHIFT) & 0xF, p >> ENTRY_FINAL_SHIFT]
}

/// Converging-photon clustering (Sec. 3.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cluster {
    None,
    /// Convergence tested only at the last level above the photon buffer.
    Last,
    /// Convergence tested at every level.
    All,
}

impl Cluster {
    pub fn parse(name: &str) -> Option<Cluster> {
        match name {
            "none" => Some(Cluster::None),
            "last" => Some(Cluster::Last),
            "all" => Some(Cluster::All),
            _ => None,
        }
    }
    fn tests(self, level: u32) -> bool {
        match self {
            Cluster::None => false,
            Cluster::Last => level == 1,
            Cluster::All => true,
        }
    }
}

/// The traversal path's name (`xfb` or `compute`) as a [`CompactionPath`].
pub fn parse_path(name: &str) -> Option<CompactionPath> {
    match name {
        "xfb" => Some(CompactionPath::TransformFeedback),
        "compute" => Some(CompactionPath::Compute),
        _ => None,
    }
}

/// Features the traversal path needs.
pub fn path_features(path: CompactionPath) -> &'static [Feature] {
    match path {
        CompactionPath::TransformFeedback => {
            &[Feature::GeometryShader, Feature::TransformFeedback, Feature::TransformFeedbackDraw]
        }
        CompactionPath::Compute => &[],
    }
}

/// (P, L): the photon buffer side N padded to a power of two P ≥ 32 (padding texels hold no
/// photon), and the number of levels above it, the top one TOP_SIDE².
pub fn levels(n: u32) -> (u32, u32) {
    let p = n.max(2 * TOP_SIDE).next_power_of_two();
    (p, (p / TOP_SIDE).trailing_zeros())
}

/// The hierarchy images: level k (1..=L) in mip k-1 of each. The images are only held to keep
/// the views alive.
#[allow(dead_code)]
struct Pyramid {
    /// (summed power, photon count).
    power: Image,
    /// (summed position, 0).
    position: Image,
    /// Caustic-map texel bounding box (min x, min y, max x, max y) of the subtree's photons.
    texels: Image,
    /// Every mip, sampled: [power, position, texels].
    all: [ImageView; 3],
    /// One view per mip (level k at index k-1): [power, position, texels].
    mips: Vec<[ImageView; 3]>,
}

pub struct Hierarchy {
    pub path: CompactionPath,
    pub cluster: Cluster,
    /// Photon buffer side N, padded side P and levels L.
    pub n: u32,
    pub padded: u32,
    pub levels: u32,
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
    finalize: Option<Pipeline>,
    splat: Pipeline,
}

impl Hierarchy {
    pub fn new(
        ctx: &Context,
        sh: &ShaderCompiler,
        n: u32,
        lights: u32,
        path: CompactionPath,
        cluster: Cluster,
    ) -> Result<Hierarchy> {
        ctx.require(&format!("technique `hcm` with --path {}", path.name()), path_features(path))?;
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
        ctx.upload_buffer(&seed.data, bytemuck::cast_slice(&seed_entries))?;
        let count = seed_entries.len() as u32;
        let header: [u32; 12] = [count, count, 0, 0, count.div_ceil(64), 1, 1, 0, count, 1, 0, 0];
        ctx.upload_buffer(&seed.counter, bytemuck::cast_slice(&header))?;
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

        let build = Pipeline::compute(
            ctx,
            "hierarchy.build",
            &sh.compile("hierarchy/build.comp", &[])?,
            &[
                K::UniformBuffer,
                K::UniformBuffer,
                K::SampledImage,
                K::SampledImage,
                K::SampledImage,
                K::SampledImage,
                K::SampledImage,
                K::StorageImage,
                K::StorageImage,
                K::StorageImage,
            ],
        )?;
        let entries = VertexLayout {
            stride: ENTRY_BYTES as u32,
            attributes: vec![VertexAttribute { location: 0, format: Format::R32_UINT, offset: 0 }],
        };
        let textures = [K::UniformBuffer, K::UniformBuffer, K::SampledImage, K::SampledImage, K::SampledImage];
        let (traverse, finalize) = match path {
            CompactionPath::TransformFeedback => {
                let mut d = GraphicsDesc::new("hierarchy.traverse", sh.compile("hierarchy/traverse.vert", &[])?, None);
                d.geometry = Some(sh.compile("hierarchy/traverse.geom", &[])?);
                d.bindings = textures.to_vec();
                d.topology = Topology::Points;
                d.rasterizer_discard = true;
                d.vertex_layout = Some(entries.clone());
                (Pipeline::graphics(ctx, &d)?, None)
            }
            CompactionPath::Compute => {
                let mut b = textures.to_vec();
                b.extend([K::StorageBuffer; 4]);
                let traverse =
                    Pipeline::compute(ctx, "hierarchy.traverse", &sh.compile("hierarchy/traverse.comp", &[])?, &b)?;
                let finalize = Pipeline::compute(
                    ctx,
                    "hierarchy.finalize",
                    &sh.compile("vkcore/compact_finalize.comp", &[])?,
                    &[K::StorageBuffer],
                )?;
                (traverse, Some(finalize))
            }
        };
        let mut splat = GraphicsDesc::new(
            "splat_hierarchy",
            sh.compile("photons/splat.vert", &[("HIERARCHY", "1")])?,
            Some(sh.compile("photons/splat.frag", &[])?),
        );
        splat.bindings = vec![
            K::UniformBuffer,
            K::UniformBuffer,
            K::SampledImage,
            K::SampledImage,
            K::SampledImage,
            K::SampledImage,
        ];
        splat.vertex_layout = Some(entries);
        splat.topology = Topology::Points;
        splat.blend = Blend::Additive;
        splat.color_formats = vec![COLOR];
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

    /// Builds the hierarchy over light `l`'s photon buffer and traverses it (Sec. 3.1-3.2).
    pub fn record_traversal(&self, f: &mut Frame, inp: &Inputs, pt: &PhotonTargets, l: u32) -> Result<()> {
        let py = &self.pyramid;
        let ubos = || {
            [
                Use::buffer(inp.frame_uniforms, Access::UNIFORM_READ),
                Use::buffer(inp.caustic_uniforms, Access::UNIFORM_READ),
            ]
        };
        let push = |level: u32, cluster: bool| ObjectConstants {
            info: [level, l, cluster as u32, self.n],
            ..Default::default()
        };
        for k in 1..=self.levels {
            let out = &py.mips[k as usize - 1];
            let children: [&ImageView; 3] = if k == 1 {
                [&self.dummy.view, &self.dummy.view, &self.dummy.view]
            } else {
                let c = &py.mips[k as usize - 2];
                [&c[0], &c[1], &c[2]]
            };
            let mut uses = Vec::from(ubos());
            uses.extend([
                Use::view(&pt.position.view, Access::SHADER_READ),
                Use::view(&pt.power.view, Access::SHADER_READ),
            ]);
            if k == 1 {
                uses.push(Use::view(&self.dummy.view, Access::SHADER_READ));
            } else {
                uses.extend(children.iter().map(|v| Use::view(v, Access::SHADER_READ)));
            }
            uses.extend(out.iter().map(|v| Use::view(v, Access::COMPUTE_READ_WRITE)));
            f.pass(&format!("hierarchy.build.level{k}.light{l}"), &uses, |cmd| {
                cmd.bind_pipeline(&self.build);
                cmd.bind(&[
                    Bind::Uniform(inp.frame_uniforms),
                    Bind::Uniform(inp.caustic_uniforms),
                    Bind::Sampled(&pt.position.view, inp.nearest),
                    Bind::Sampled(&pt.power.view, inp.nearest),
                    Bind::Sampled(children[0], inp.nearest),
                    Bind::Sampled(children[1], inp.nearest),
                    Bind::Sampled(children[2], inp.nearest),
                    Bind::Storage(&out[0]),
                    Bind::Storage(&out[1]),
                    Bind::Storage(&out[2]),
                ])?;
                cmd.push(&push(k, false))?;
                let side = self.padded >> k;
                cmd.dispatch(side.div_ceil(8), side.div_ceil(8), 1);
                Ok(())
            })?;
        }
        // The paper zeroes its counters before every traversal; so do we (both paths).
        let counters: Vec<Use> = self.lists.iter().map(|s| Use::buffer(&s.counter, Access::TRANSFER_WRITE)).collect();
        f.pass(&format!("hierarchy.reset.light{l}"), &counters, |cmd| {
            for s in &self.lists {
                match self.path {
                    CompactionPath::TransformFeedback => cmd.fill_buffer(&s.counter, 0),
                    CompactionPath::Compute => {
                        let header: Vec<u8> = [0u32, s.capacity, 0, 0].iter().flat_map(|x| x.to_le_bytes()).collect();
                        cmd.update_buffer(&s.counter, 0, &header)?;
                    }
                }
            }
            Ok(())
        })?;
        let textures = || {
            [
                Use::view(&pt.position.view, Access::SHADER_READ),
                Use::view(&py.all[0], Access::SHADER_READ),
                Use::view(&py.all[2], Access::SHADER_READ),
            ]
        };
        for k in (1..=self.levels).rev() {
            let input = if k == self.levels { &self.seed } else { &self.lists[k as usize] };
            let out = &self.lists[k as usize - 1];
            let mut uses = Vec::from(ubos());
            uses.extend(textures());
            let binds = || {
                vec![
                    Bind::Uniform(inp.frame_uniforms),
                    Bind::Uniform(inp.caustic_uniforms),
                    Bind::Sampled(&pt.position.view, inp.nearest),
                    Bind::Sampled(&py.all[0], inp.nearest),
                    Bind::Sampled(&py.all[2], inp.nearest),
                ]
            };
            let name = format!("hierarchy.traverse.level{k}.light{l}");
            let cluster = self.cluster.tests(k);
            match self.path {
                CompactionPath::TransformFeedback => {
                    uses.push(Use::buffer(&input.data, Access::VERTEX_INPUT));
                    if k != self.levels {
                        uses.push(Use::buffer(&input.counter, Access::INDIRECT));
                    }
                    uses.push(Use::buffer(&out.data, Access::XFB_WRITE));
                    uses.push(Use::buffer(&out.counter, Access::XFB_COUNTER));
                    f.pass(&name, &uses, |cmd| {
                        cmd.begin_rendering(&Targets::none())?;
                        cmd.bind_pipeline(&self.traverse);
                        cmd.bind(&binds())?;
                        cmd.push(&push(k, cluster))?;
                        cmd.bind_vertex_buffer(&input.data, 0);
                        cmd.bind_xfb_buffers(&[&out.data])?;
                        // No counter buffers at begin: capture starts at offset 0.
                        cmd.begin_xfb(&[], false)?;
                        if k == self.levels {
                            cmd.draw(self.seed.capacity, 1, 0, 0);
                        } else {
                            cmd.draw_indirect_byte_count(1, &input.counter, ENTRY_BYTES as u32)?;
                        }
                        cmd.end_xfb(&[&out.counter])?;
                        cmd.end_rendering();
                        Ok(())
                    })?;
                }
                CompactionPath::Compute => {
                    uses.push(Use::buffer(&input.data, Access::STORAGE_READ));
                    uses.push(Use::buffer(&input.counter, Access::INDIRECT));
                    uses.push(Use::buffer(&input.counter, Access::STORAGE_READ));
                    uses.push(Use::buffer(&out.data, Access::COMPUTE_READ_WRITE));
                    uses.push(Use::buffer(&out.counter, Access::COMPUTE_READ_WRITE));
                    f.pass(&name, &uses, |cmd| {
                        cmd.bind_pipeline(&self.traverse);
                        let mut b = binds();
                        b.extend([
                            Bind::Buffer(&input.data),
                            Bind::Buffer(&input.counter),
                            Bind::Buffer(&out.data),
                            Bind::Buffer(&out.counter),
                        ]);
                        cmd.bind(&b)?;
                        cmd.push(&push(k, cluster))?;
                        cmd.dispatch_indirect(&input.counter, 16);
                        Ok(())
                    })?;
                    let finalize = self.finalize.as_ref().ok_or_else(|| anyhow::anyhow!("no finalize pipeline"))?;
                    let uses = [Use::buffer(&out.counter, Access::COMPUTE_READ_WRITE)];
                    f.pass(&format!("hierarchy.finalize.level{k}.light{l}"), &uses, |cmd| {
                        cmd.bind_pipeline(finalize);
                        cmd.bind(&[Bind::Buffer(&out.counter)])?;
                        cmd.dispatch(1, 1, 1);
                        Ok(())
                    })?;
                }
            }
        }
        // Keep this light's list sizes for the photon-count tables (read after the frame).
        let mut uses: Vec<Use> = self.lists.iter().map(|s| Use::buffer(&s.counter, Access::TRANSFER_READ)).collect();
        uses.push(Use::buffer(&self.counts, Access::TRANSFER_WRITE));
        f.pass(&format!("hierarchy.counts.light{l}"), &uses, |cmd| {
            for (k, s) in self.lists.iter().enumerate() {
                let slot = (l.min(self.lights.max(1) - 1) * self.levels + k as u32) as u64 * 4;
                cmd.copy_buffer_region(&s.counter, 0, &self.counts, slot, 4);
            }
            Ok(())
        })?;
        Ok(())
    }

    /// Splats the traversal's final list (photons and clusters) into `cmap`: one layer, or the
    /// `layers` levels of the multi-resolution map, each splat picking its layer (gl_Layer).
    pub fn record_splat(
        &self,
        f: &mut Frame,
        inp: &Inputs,
        pt: &PhotonTargets,
        cmap: &ImageView,
        layers: u32,
        l: u32,
    ) -> Result<()> {
        let py = &self.pyramid;
        let list = &self.lists[0];
        let uses = [
            Use::buffer(inp.frame_uniforms, Access::UNIFORM_READ),
            Use::buffer(inp.caustic_uniforms, Access::UNIFORM_READ),
            Use::view(&pt.position.view, Access::SHADER_READ),
            Use::view(&pt.power.view, Access::SHADER_READ),
            Use::view(&py.all[0], Access::SHADER_READ),
            Use::view(&py.all[1], Access::SHADER_READ),
            Use::buffer(&list.data, Access::VERTEX_INPUT),
            Use::buffer(&list.counter, Access::INDIRECT),
            Use::view(cmap, Access::COLOR_ATTACHMENT),
        ];
        f.pass(&format!("splat.light{l}"), &uses, |cmd| {
            cmd.begin_rendering(&Targets::color(cmap, Some([0.0; 4])).layered(layers))?;
            cmd.bind_pipeline(&self.splat);
            cmd.bind(&[
                Bind::Uniform(inp.frame_uniforms),
                Bind::Uniform(inp.caustic_uniforms),
                Bind::Sampled(&pt.position.view, inp.nearest),
                Bind::Sampled(&pt.power.view, inp.nearest),
                Bind::Sampled(&py.all[0], inp.nearest),
                Bind::Sampled(&py.all[1], inp.nearest),
            ])?;
            cmd.push(&ObjectConstants { info: [0, l, 0, self.n], ..Default::default() })?;
            cmd.bind_vertex_buffer(&list.data, 0);
            match self.path {
                CompactionPath::TransformFeedback => {
                    cmd.draw_indirect_byte_count(1, &list.counter, ENTRY_BYTES as u32)?
                }
                // The draw arguments of compact_counter.glsl start at byte 32.
                CompactionPath::Compute => cmd.draw_indirect(&list.counter, 32),
            }
            cmd.end_rendering();
            Ok(())
        })?;
        Ok(())
    }

    /// What the compute splat reads: the hierarchy and the traversal's final list.
    pub fn final_list(&self) -> super::compute_splat::Photons<'_> {
        super::compute_splat::Photons::List {
            power: &self.pyramid.all[0],
            position: &self.pyramid.all[1],
            list: &self.lists[0],
        }
    }

    /// Per light: the size of each list from level L (the seed) down to 0 (the splatted
    /// photons and clusters) after the last traversal.
    pub fn list_sizes(&self, ctx: &Context) -> Result<Vec<Vec<u64>>> {
        let raw: Vec<u32> = ctx.read_buffer_as(&self.counts)?;
        let per = self.levels as usize;
        Ok((0..self.lights.max(1) as usize)
            .map(|l| {
                let mut v = vec![self.seed.capacity as u64];
                for k in (0..per).rev() {
                    let c = raw.get(l * per + k).copied().unwrap_or(0) as u64;
                    v.push(match self.path {
                        CompactionPath::TransformFeedback => c / ENTRY_BYTES,
                        CompactionPath::Compute => c.min(self.lists[k].capacity as u64),
                    });
                }
                v
            })
            .collect())
    }

    /// The final list of the last traversal (photons at level 0, clusters flagged final).
    pub fn final_entries(&self, ctx: &Context) -> Result<Vec<[u32; 4]>> {
        Ok(self.lists[0].read_as::<u32>(ctx)?.into_iter().map(unpack_entry).collect())
    }
}

impl Hierarchy {
    /// `hierarchy.exr` for the light traversed last: every level of the photon hierarchy (level
    /// 0 is the photon buffer), level k in the top-left (P/2^k)² corner of layers
    /// `level<k>.power` (R, G, B, count), `level<k>.position` (mean X, Y, Z of the subtree's
    /// photons) and `level<k>.texels` (caustic-map texel box).
    pub fn dump_levels(&self, ctx: &Context) -> Result<ImageF32> {
        let side = self.padded / 2;
        let mut layers = vec![];
        for k in 1..=self.levels {
            let s = (self.padded >> k) as usize;
            let read = |i: &Image| ctx.read_image_f32(i, k - 1, 0);
            let (power, position, texels) =
                (read(&self.pyramid.power)?, read(&self.pyramid.position)?, read(&self.pyramid.texels)?);
            let place = |src: &[f32], pick: &dyn Fn(&[f32]) -> Vec<f32>, nc: usize| {
                let mut out = vec![0.0f32; side as usize * side as usize * nc];
                for y in 0..s {
                    for x in 0..s {
                        let v = pick(&src[(y * s + x) * 4..(y * s + x) * 4 + 4]);
                        let o = (y * side as usize + x) * nc;
                        out[o..o + nc].copy_from_slice(&v);
                    }
                }
                out
            };
            let mean = |p: &[f32]| -> Vec<f32> { p[..3].to_vec() };
            let counts: Vec<f32> = power.chunks(4).map(|p| p[3]).collect();
            let mut mean_pos = position.clone();
            for (i, c) in counts.iter().enumerate() {
                for v in &mut mean_pos[i * 4..i * 4 + 3] {
                    *v /= c.max(1.0);
                }
            }
            layers.push(Layer::new(
                Some(&format!("level{k}.power")),
                &["R", "G", "B", "count"],
                place(&power, &|p| p.to_vec(), 4),
            ));
            layers.push(Layer::new(Some(&format!("level{k}.position")), &["X", "Y", "Z"], place(&mean_pos, &mean, 3)));
            layers.push(Layer::new(
                Some(&format!("level{k}.texels")),
                &["min_x", "min_y", "max_x", "max_y"],
                place(&texels, &|p| p.to_vec(), 4),
            ));
        }
        Ok(ImageF32 { width: side, height: side, layers })
    }

    /// The traversal's lists of the light traversed last: `[k]` is the list the step at level
    /// k+1 wrote (level-k nodes and the clusters finished above), `[0]` what was splatted.
    pub fn read_lists(&self, ctx: &Context) -> Result<Vec<Vec<[u32; 4]>>> {
        let read = |s: &CompactStream| -> vkcore::Result<Vec<[u32; 4]>> {
            Ok(s.read_as::<u32>(ctx)?.into_iter().map(unpack_entry).collect())
        };
        Ok(self.lists.iter().map(read).collect::<vkcore::Result<_>>()?)
    }
}

/// `hierarchy_lists.exr` from each light's [`Hierarchy::read_lists`]: layer `light<l>.list<k>`
/// holds light l's list k, an entry per pixel in row-major order: x, y, level, final (1 = a
/// cluster of converging photons), valid (1 = an entry; the rest of the image is padding).
pub fn lists_image(per_light: &[Vec<Vec<[u32; 4]>>]) -> ImageF32 {
    let mut lists = vec![];
    for (l, light) in per_light.iter().enumerate() {
        for (k, list) in light.iter().enumerate() {
            let records = list.iter().map(|e| vec![e[0] as f32, e[1] as f32, e[2] as f32, e[3] as f32, 1.0]).collect();
            lists.push((format!("light{l}.list{k}"), records));
        }
    }
    super::records_image(lists, &["x", "y", "level", "final", "valid"])
}

/// What the hierarchy passes read besides the photon buffer.
pub struct Inputs<'a> {
    pub frame_uniforms: &'a Buffer,
    pub caustic_uniforms: &'a Buffer,
    pub nearest: &'a Sampler,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_pad_to_a_power_of_two_with_a_16_squared_top() {
        assert_eq!(levels(64), (64, 2));
        assert_eq!(levels(100), (128, 3));
        assert_eq!(levels(1024), (1024, 6));
        assert_eq!(levels(4096), (4096, 8));
        assert_eq!(levels(17), (32, 1));
    }

    #[test]
    fn entries_round_trip_and_match_the_glsl() {
        for e in [[0, 0, 0, 0], [4095, 4095, 8, 1], [17, 4000, 3, 0], [1, 2, 15, 1]] {
            assert_eq!(unpack_entry(pack_entry(e)), e);
        }
        let glsl =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shaders_glsl/hierarchy/entry.glsl"))
                .expect("entry.glsl");
        for (name, v) in [("Y", ENTRY_Y_SHIFT), ("LEVEL", ENTRY_LEVEL_SHIFT), ("FINAL", ENTRY_FINAL_SHIFT)] {
            assert!(glsl.contains(&format!("#define ENTRY_{name}_SHIFT {v}u")), "entry.glsl: ENTRY_{name}_SHIFT");
        }
        // The largest photon buffer and its deepest level fit the fields.
        let (p, l) = levels(4096);
        assert!(p <= MAX_SIDE && l < 16);
    }

    #[test]
    fn clustering_levels() {
        assert!(!Cluster::None.tests(1));
        assert!(Cluster::Last.tests(1) && !Cluster::Last.tests(2));
        assert!(Cluster::All.tests(1) && Cluster::All.tests(5));
    }
}
