//! The `subcount` binary: the command line lives in the library ([`subcount_cli::main`]).

fn main() -> std::process::ExitCode {
    subcount_cli::main()
}
