//! `rtfpga formats`: the number-format catalogue.

use anyhow::Result;
use clap::Args as ClapArgs;

#[derive(ClapArgs)]
pub struct Args {
    /// Machine-readable output.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<()> {
    let cat = hw_model::catalogue();
    if a.json {
        let rows: Vec<_> = cat
            .iter()
            .map(|f| serde_json::json!({"name": f.name, "format": f.format, "width": f.format.width(), "description": f.description}))
            .collect();
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(());
    }
    println!("| name | kind | width | description |\n|---|---|---|---|");
    for f in cat {
        let kind = match f.format {
            hw_model::Format::Float { exp, man } => format!("float E{exp} M{man}"),
            hw_model::Format::Fixed {
                int,
                frac,
                quant,
                overflow,
            } => format!("fixed <{},{}> {quant:?} {overflow:?}", int + frac, int),
        };
        println!(
            "| {} | {} | {} | {} |",
            f.name,
            kind,
            f.format.width(),
            f.description
        );
    }
    Ok(())
}
