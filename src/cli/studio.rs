//! `moyo studio`: starts the live design page (see [`moyo::studio`]) on a
//! description file, a template or the default design, prints its address
//! and serves until stopped.

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::time::Duration;

use moyo::studio::{Studio, StudioLimits, StudioOptions};
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
    /// Most memory (MiB) the studio may hold while it renders an edit; an
    /// edit that needs more is refused and the last good design stays
    /// (read from the system on Linux; elsewhere not checked).
    #[arg(long, value_name = "MIB", default_value_t = 4096, value_parser = clap::value_parser!(u64).range(64..=1 << 30))]
    memory_mb: u64,
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
        (None, None) => templates::get(templates::DEFAULT)?.text.to_string(),
    };
    let studio = Studio::start(StudioOptions {
        folder: PathBuf::from("."),
        text,
        addr: SocketAddr::new(args.host, args.port),
        limits: StudioLimits {
            memory: args.memory_mb << 20,
            ..limits()?
        },
    })?;
    eprintln!(
        "moyo studio: open {} (Ctrl-C to stop; files are read and written in {})",
        studio.url(),
        std::env::current_dir().map_or_else(|_| ".".into(), |d| d.display().to_string())
    );
    studio.wait()?;
    Ok(())
}

/// Shortens the header deadline for a test of the command, which must
/// not wait the default's 10 s for stalled connections to be let go.
/// Not a setting for users, so not among the flags.
const HEADER_TIMEOUT_VAR: &str = "MOYO_STUDIO_HEADER_TIMEOUT_MS";

/// The default limits, but for `MOYO_STUDIO_HEADER_TIMEOUT_MS`.
fn limits() -> Result<StudioLimits, CliError> {
    let mut limits = StudioLimits::default();
    if let Some(ms) = std::env::var_os(HEADER_TIMEOUT_VAR) {
        let ms = ms
            .to_str()
            .and_then(|ms| ms.parse::<u64>().ok())
            .ok_or_else(|| {
                CliError::Message(format!(
                    "{HEADER_TIMEOUT_VAR}: give a whole number of milliseconds, got {ms:?}"
                ))
            })?;
        limits.header_timeout = Duration::from_millis(ms);
    }
    Ok(limits)
}
