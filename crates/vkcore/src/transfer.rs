//! Uploads and readbacks through staging buffers: whole buffers, and any mip level / array
//! layer of an image. Each is its own small frame, waited for.

use crate::buffer::{Buffer, Memory};
use crate::context::Context;
use crate::error::{Result, VkError};
use crate::frame::{FrameOptions, Use};
use crate::image::{texel_size, Image};
use crate::tracker::Access;

impl Context {
    /// Creates a device buffer holding `data`.
    pub fn buffer_with_data(&self, name: &str, data: &[u8]) -> Result<Buffer> {
        let buf = Buffer::new(self, name, data.len() as u64, Memory::Gpu)?;
        self.upload_buffer(&buf, data)?;
        Ok(buf)
    }

    /// Copies `data` into the start of `dst`.
    pub fn upload_buffer(&self, dst: &Buffer, data: &[u8]) -> Result<()> {
        if data.len() as u64 > dst.size() {
            return Err(VkError::Invalid(format!(
                "upload of {} bytes into `{}` ({} bytes)",
                data.len(),
                dst.name(),
                dst.size()
            )));
        }
        if data.is_empty() {
            return Ok(());
        }
        let mut staging = Buffer::new(self, "staging upload", data.len() as u64, Memory::Upload)?;
        staging.write_mapped(0, data)?;
        let mut f = self.frame(FrameOptions::default())?;
        f.pass("upload")
            .uses([Use::buffer(&staging, Access::TRANSFER_READ), Use::buffer(dst, Access::TRANSFER_WRITE)])
            .record(|c| {
                c.copy_buffer(&staging, dst, data.len() as u64);
                Ok(())
            })?;
        f.submit()?;
        Ok(())
    }

    /// Reads the whole of `src` back.
    pub fn read_buffer(&self, src: &Buffer) -> Result<Vec<u8>> {
        let staging = Buffer::new(self, "staging readback", src.size(), Memory::Readback)?;
        let mut f = self.frame(FrameOptions::default())?;
        f.pass("readback")
            .uses([Use::buffer(src, Access::TRANSFER_READ), Use::buffer(&staging, Access::TRANSFER_WRITE)])
            .record(|c| {
                c.copy_buffer(src, &staging, src.size());
                Ok(())
            })?;
        f.submit()?;
        let bytes = staging.mapped().ok_or_else(|| VkError::Invalid("readback buffer is not mapped".into()))?;
        Ok(bytes[..src.size() as usize].to_vec())
    }

    /// Reads `src` back as `T`s.
    pub fn read_buffer_as<T: bytemuck::Pod>(&self, src: &Buffer) -> Result<Vec<T>> {
        let bytes = self.read_buffer(src)?;
        let n = bytes.len() / std::mem::size_of::<T>();
        Ok(bytemuck::pod_collect_to_vec(&bytes[..n * std::mem::size_of::<T>()]))
    }

    fn image_bytes(image: &Image, mip: u32, layer: u32) -> Result<u64> {
        if mip >= image.desc.mip_levels || layer >= image.desc.array_layers {
            return Err(VkError::Invalid(format!(
                "image `{}` has {} mips and {} layers; asked for mip {mip} layer {layer}",
                image.desc.name, image.desc.mip_levels, image.desc.array_layers
            )));
        }
        let ts = texel_size(image.desc.format).ok_or_else(|| {
            VkError::Invalid(format!("image `{}`: format {:?} cannot be read back", image.desc.name, image.desc.format))
        })?;
        let (w, h) = image.mip_extent(mip);
        Ok(w as u64 * h as u64 * ts as u64)
    }

    /// Writes tightly packed texels into one mip/layer of `image`.
    pub fn upload_image(&self, image: &Image, mip: u32, layer: u32, data: &[u8]) -> Result<()> {
        let bytes = Self::image_bytes(image, mip, layer)?;
        if data.len() as u64 != bytes {
            return Err(VkError::Invalid(format!(
                "upload into `{}` mip {mip}: {} bytes given, {bytes} expected",
                image.desc.name,
                data.len()
            )));
        }
        let mut staging = Buffer::new(self, "staging image upload", bytes, Memory::Upload)?;
        staging.write_mapped(0, data)?;
        let mut f = self.frame(FrameOptions::default())?;
        f.pass("upload image")
            .uses([
                Use::buffer(&staging, Access::TRANSFER_READ),
                Use::image(image, mip..mip + 1, layer..layer + 1, Access::TRANSFER_WRITE),
            ])
            .record(|c| {
                c.copy_buffer_to_image(&staging, image, mip, layer);
                Ok(())
            })?;
        f.submit()?;
        Ok(())
    }

    /// Reads one mip/layer of `image` back, tightly packed, row 0 first.
    pub fn read_image(&self, image: &Image, mip: u32, layer: u32) -> Result<Vec<u8>> {
        let bytes = Self::image_bytes(image, mip, layer)?;
        let staging = Buffer::new(self, "staging image readback", bytes, Memory::Readback)?;
        let mut f = self.frame(FrameOptions::default())?;
        f.pass("readback image")
            .uses([
                Use::image(image, mip..mip + 1, layer..layer + 1, Access::TRANSFER_READ),
                Use::buffer(&staging, Access::TRANSFER_WRITE),
            ])
            .record(|c| {
                c.copy_image_to_buffer(image, mip, layer, &staging);
                Ok(())
            })?;
        f.pass("readback.host").uses([Use::buffer(&staging, Access::HOST_READ)]).record(|_| Ok(()))?;
        f.submit()?;
        let m = staging.mapped().ok_or_else(|| VkError::Invalid("readback buffer is not mapped".into()))?;
        Ok(m[..bytes as usize].to_vec())
    }

    /// `read_image` as f32 texels (for R32/RG32/RGBA32_SFLOAT and D32 images).
    pub fn read_image_f32(&self, image: &Image, mip: u32, layer: u32) -> Result<Vec<f32>> {
        Ok(bytemuck::pod_collect_to_vec(&self.read_image(image, mip, layer)?))
    }
}

impl Context {
    /// The device's buffer-to-buffer copy bandwidth, GB/s of bytes read plus bytes written: the
    /// fastest of three timed copies of `bytes` between two device buffers (None without
    /// timestamps). Made for the bench's plausibility rule on copies.
    pub fn copy_bandwidth(&self, bytes: u64) -> Result<Option<f64>> {
        if !self.info().has(crate::Feature::Timestamps) {
            return Ok(None);
        }
        let a = Buffer::new(self, "bandwidth source", bytes, Memory::Gpu)?;
        let b = Buffer::new(self, "bandwidth destination", bytes, Memory::Gpu)?;
        let mut f = self.frame(FrameOptions { timestamps: true, ..Default::default() })?;
        f.pass("bandwidth.fill").uses([Use::buffer(&a, Access::TRANSFER_WRITE)]).record(|c| {
            c.fill_buffer(&a, 0x3f80_0000);
            Ok(())
        })?;
        for k in 0..3 {
            let (src, dst) = if k % 2 == 0 { (&a, &b) } else { (&b, &a) };
            f.pass("bandwidth.copy")
                .uses([Use::buffer(src, Access::TRANSFER_READ), Use::buffer(dst, Access::TRANSFER_WRITE)])
                .record(|c| {
                    c.copy_buffer(src, dst, bytes);
                    Ok(())
                })?;
        }
        let report = f.submit()?;
        let best = report
            .passes
            .iter()
            .filter(|p| p.name == "bandwidth.copy")
            .filter_map(|p| p.gpu_ms)
            .filter(|ms| *ms > 0.0)
            .reduce(f64::min);
        Ok(best.map(|ms| 2.0 * bytes as f64 / (ms * 1e-3) / 1e9))
    }
}
