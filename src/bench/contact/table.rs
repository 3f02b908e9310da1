//! The contact rows as fixed-width text tables, for `tribosim bench contact`.

use super::{
    CAPPED_HARDNESS_PA, CAPPED_YIELD_FACTOR, CAPPED_YIELD_PRESSURE_PA, ContactCase, ContactRow,
    Reference, TIGHT_TOLERANCE, ToleranceRow, paper_case,
};

fn header(case: ContactCase, reference: &Reference) -> String {
    let against = match reference.n {
        None => String::from("Hertz's analytic solution"),
        Some(n) => format!("our own N = {n} solution of the same case"),
    };
    match case {
        ContactCase::Hertz => format!(
            "Hertz, paper case {}; solve s from the coarse-to-fine start, uniform s from the uniform pressure; errors against {against}\n",
            paper_case()
        ),
        ContactCase::Capped => format!(
            "Capped Hertz, the same case with p <= Y = {} MPa / {CAPPED_YIELD_FACTOR} = {:.2} MPa; no analytic answer: errors against {against} (err p_max = p_max / Y - 1)\n",
            CAPPED_HARDNESS_PA / 1e6,
            CAPPED_YIELD_PRESSURE_PA / 1e6
        ),
    }
}

fn optional(value: Option<f64>) -> String {
    value.map_or_else(|| String::from("-"), |v| format!("{v:+.3e}"))
}

/// The grid rows as fixed-width tables, one per case.
pub fn table(rows: &[ContactRow]) -> String {
    let mut out = String::new();
    for case in ContactCase::ALL {
        let Some(first) = rows.iter().find(|r| r.case == case) else {
            continue;
        };
        out += &header(case, &first.reference);
        out += "     N   wall s  build s  solve s  iters  applies  uniform s  iters  FFT pair ms  iter/pair   err p_max    err area   err delta  err plastic\n";
        for r in rows.iter().filter(|r| r.case == case) {
            out += &format!(
                "{:>6} {:>8.4} {:>8.4} {:>8.4} {:>6} {:>8} {:>10.4} {:>6} {:>12.3} {:>10.2} {:>+11.3e} {:>+11.3e} {:>+11.3e} {:>12}\n",
                r.n,
                r.wall_s,
                r.build_s,
                r.solve_s,
                r.iterations,
                r.applies,
                r.uniform_solve_s,
                r.uniform_iterations,
                r.fft_pair_s * 1e3,
                r.iteration_per_fft_pair,
                r.err_pmax,
                r.err_area,
                r.err_delta,
                optional(r.err_plastic_area),
            );
        }
        out += "\n";
    }
    out
}

/// The tolerance rows as a fixed-width table.
pub fn tolerance_table(rows: &[ToleranceRow]) -> String {
    let mut out = format!(
        "Tolerance study (errors against each case's reference as above; err solve = max |p - p*| / max p*, p* solved to {TIGHT_TOLERANCE:.0e} on the same grid)\n\
         \x20  case      N  tolerance  solve s  iters  applies    residual   err p_max    err area   err delta  err plastic   err solve\n",
    );
    for r in rows {
        out += &format!(
            "{:>7} {:>6} {:>10.0e} {:>8.4} {:>6} {:>8} {:>11.3e} {:>+11.3e} {:>+11.3e} {:>+11.3e} {:>12} {:>11.3e}\n",
            r.case.name(),
            r.n,
            r.tolerance,
            r.solve_s,
            r.iterations,
            r.applies,
            r.residual,
            r.err_pmax,
            r.err_area,
            r.err_delta,
            optional(r.err_plastic_area),
            r.err_solve,
        );
    }
    out
}
