//! `causticlab variants`: the registry of variants (crates/caustics/src/techniques/variants.toml),
//! as a Markdown table for readers or one line per row for scripts.

use crate::cli::VariantsArgs;
use anyhow::Result;
use caustics::techniques::variants::{registry, Variant};

pub fn run(args: &VariantsArgs) -> Result<()> {
    let rows: Vec<Variant> = registry()?.into_iter().filter(|v| !args.quality || v.quality).collect();
    if args.lines {
        // name|label|scene,scene|flags|needs: what scripts/same_maps.sh and quality_table.sh
        // read (needs: the device features beyond the technique's, `-` for none).
        for v in &rows {
            println!("{}|{}|{}|{}|{}", v.name, v.label, v.scenes().join(","), v.flags().join(" "), v.needs_names());
        }
        return Ok(());
    }
    println!("| name | label | paper | section | default | stated (power, rel. RMSE) | flags | needs |");
    println!("|---|---|---|---|---|---|---|---|");
    for v in &rows {
        let stated = v.stated.map_or("–".to_string(), |s| format!("{:e}, {}", s.power, s.rel_rmse));
        let default = if v.default { "yes" } else { "" };
        println!(
            "| `{}` | {} | {} | {} | {default} | {stated} | `{}` | {} |",
            v.name,
            v.label,
            v.paper,
            v.section,
            v.flags().join(" "),
            v.needs_names()
        );
    }
    Ok(())
}
