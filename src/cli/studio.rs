//! `moyo studio`: starts the live design page (see [`moyo::studio`]) on a
//! description file, a template or the default design, prints its address
//! and serves until stopped.

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;

use moyo::studio::{Studio, StudioOptions};
use moyo::templates;
use moyo::{Format, ValidSpec};

use super::CliError;

#[derive(clap::Args)]
pub(crate) struct StudioArgs {
    /// Scene description file to start from (TOML, or JSON, which the
    /// studio turns into TOML).
    scene: Option<PathBuf>,
    /// Start from a built-in template instead.
    #[arg(short, long, conflicts_with = "scene")]
    template: Option<String>,
    /// Port to listen on (0: any free port).
    #[arg(long, default_value_t = 7878)]
    port: u16,
    /// Address to listen on. Only this machine can reach the default;
    /// another address lets others on the network edit your files.
    #[arg(long, default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    host: IpAddr,
}

/// `moyo studio`.
pub(crate) fn studio(args: &StudioArgs) -> Result<(), CliError> {
    let text = match (&args.scene, &args.template) {
        (Some(path), _) => {
            let text = moyo::input::read_text(path)
                .map_err(|e| CliError::Message(format!("{}: {e}", path.display())))?;
            match Format::from_path(path) {
                Format::Toml => text,
                // The studio edits TOML: a JSON description is written as
                // TOML once, here (it has no comments to lose).
                Format::Json => ValidSpec::parse(&text, Format::Json)
                    .map_err(|e| CliError::Message(format!("{}:{e}", path.display())))?
                    .to_toml(),
            }
        }
        (None, Some(name)) => templates::get(name)?.text.to_string(),
        (None, None) => templates::get(templates::STUDIO)?.text.to_string(),
    };
    let studio = Studio::start(StudioOptions {
        folder: PathBuf::from("."),
        text,
        addr: SocketAddr::new(args.host, args.port),
    })?;
    eprintln!(
        "moyo studio: open {} (Ctrl-C to stop; files are read and written in {})",
        studio.url(),
        std::env::current_dir().map_or_else(|_| ".".into(), |d| d.display().to_string())
    );
    studio.wait()?;
    Ok(())
}
