//! The `nctrans` binary. All of the command line (arguments, rendering, exit codes) is in
//! [`cli`]; the library (`nctrans`) never prints.

use std::process::ExitCode;

mod cli;

fn main() -> ExitCode {
    cli::main()
}
