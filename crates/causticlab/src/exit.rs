//! Exit codes and the mapping from an error chain to one of them.

use caustics::InputError;
use vkcore::VkError;

pub const OK: u8 = 0;
pub const FAILURE: u8 = 1;
/// `diff`: the two sides differ (as diff(1); any trouble comparing them is `INPUT`).
pub const DIFFERENT: u8 = 1;
/// The user's input is wrong: bad scene, unknown name, no such device, missing feature.
pub const INPUT: u8 = 2;
/// `--validate` and the validation layer reported at least one warning or error.
pub const VALIDATION: u8 = 3;
/// Standard output was closed by its reader (`| head`): 128 + SIGPIPE (13), as the shell reports a
/// program that signal stopped.
pub const CLOSED_STDOUT: u8 = 141;

/// `INPUT` when anything in the chain is the user's to fix, else `FAILURE`.
pub fn code_for(err: &anyhow::Error) -> u8 {
    let is_input = err.chain().any(|cause| {
        cause.downcast_ref::<InputError>().is_some()
            || matches!(
                cause.downcast_ref::<VkError>(),
                Some(VkError::NoDevice { .. } | VkError::AmbiguousDevice { .. } | VkError::MissingFeature { .. })
            )
    });
    if is_input {
        INPUT
    } else {
        FAILURE
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use anyhow::Context;

    #[test]
    fn input_errors_anywhere_in_the_chain_map_to_2() {
        let e = anyhow::Error::new(InputError::new("x.toml: key `a`: bad"));
        assert_eq!(code_for(&e), INPUT);
        let wrapped: anyhow::Result<()> = Err(e);
        let e = wrapped.context("loading scene").unwrap_err();
        assert_eq!(code_for(&e), INPUT);
        let e = anyhow::Error::new(VkError::NoDevice { query: "q".into(), available: String::new() });
        assert_eq!(code_for(&e), INPUT);
        let e = anyhow::Error::new(VkError::AmbiguousDevice { query: "q".into(), count: 2, matches: String::new() });
        assert_eq!(code_for(&e), INPUT);
        let e = anyhow::Error::new(VkError::MissingFeature {
            who: "t".into(),
            feature: "f",
            vulkan_name: "v",
            device: "d".into(),
        });
        assert_eq!(code_for(&e), INPUT);
    }

    #[test]
    fn other_errors_map_to_1() {
        assert_eq!(code_for(&anyhow::anyhow!("disk full")), FAILURE);
        let e = anyhow::Error::new(VkError::NoValidationLayer);
        assert_eq!(code_for(&e), FAILURE);
    }
}
