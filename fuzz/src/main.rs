//! One AFL++ fuzz binary for every input moyo reads: the target is named by
//! `MOYO_FUZZ_TARGET` (see `moyo::fuzz::Target` and README.md). An input
//! moyo refuses is fine; a panic (abort) or a hang is a finding.

fn main() {
    let name = std::env::var("MOYO_FUZZ_TARGET").unwrap_or_default();
    let Some(target) = moyo::fuzz::Target::from_name(&name) else {
        let names: Vec<&str> = moyo::fuzz::Target::ALL.iter().map(|t| t.name()).collect();
        eprintln!("set MOYO_FUZZ_TARGET to one of: {}", names.join(", "));
        std::process::exit(2);
    };
    afl::fuzz!(|data: &[u8]| {
        let _ = target.run(data);
    });
}
