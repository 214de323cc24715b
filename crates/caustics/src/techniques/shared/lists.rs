//! Reading back a traversal's compacted lists, written once for both papers that traverse one:
//! Wyman 2008's photon hierarchy (`wyman2008/traversal.rs`) and Wyman & Nichols 2009's adaptive
//! traversal (`wyman_nichols2009/adaptive/traversal.rs`). Each list is a `vkcore::CompactStream`
//! of packed `u32` entries; a counters buffer holds, light after light, what each step kept.
//! What an entry means, and the channels of its dump, stay with its paper.

use anyhow::Result;
use vkcore::{Buffer, CompactStream, Context};

/// The entries `list` kept, each unpacked from its packed `u32`.
pub fn read_packed<T>(ctx: &Context, list: &CompactStream, unpack: impl Fn(u32) -> T) -> Result<Vec<T>> {
    Ok(list.read_as::<u32>(ctx)?.into_iter().map(unpack).collect())
}

/// The counters of `counts` light by light: `per_light` each, light l's from l * `per_light`
/// on, for `lights` lights (at least one); a counter past the buffer's end reads 0.
pub fn read_counters(ctx: &Context, counts: &Buffer, lights: u32, per_light: usize) -> Result<Vec<Vec<u64>>> {
    let raw: Vec<u32> = ctx.read_buffer_as(counts)?;
    Ok(counters_per_light(&raw, lights, per_light))
}

fn counters_per_light(raw: &[u32], lights: u32, per_light: usize) -> Vec<Vec<u64>> {
    let at = |i: usize| raw.get(i).copied().unwrap_or(0) as u64;
    (0..lights.max(1) as usize).map(|l| (0..per_light).map(|k| at(l * per_light + k)).collect()).collect()
}

#[cfg(test)]
mod tests {
    use super::counters_per_light;

    #[test]
    fn counters_are_split_light_by_light_and_read_0_past_the_end() {
        let raw = [1, 2, 3, 4, 5];
        assert_eq!(counters_per_light(&raw, 2, 3), vec![vec![1, 2, 3], vec![4, 5, 0]]);
        assert_eq!(counters_per_light(&raw, 0, 2), vec![vec![1, 2]], "no lights reads one");
        assert_eq!(counters_per_light(&raw, 1, 0), vec![Vec::<u64>::new()]);
    }
}
