//! `rotor-chain-reference`: the Rust library's own numbers for the Python tests.
//!
//! Reads a JSON list of cases on stdin, computes each with `rotor_chain` directly (no Python
//! involved), and writes a JSON list of results on stdout, one per case: `{"ok": {...}}` or
//! `{"error": "<the Rust error's message>"}`. Floats are written with the shortest text that reads
//! back bit for bit, so the tests compare the binding's numbers with these exactly or to a
//! stated tolerance.
//!
//! A case is `{"chain": {n, r, k, theta_bar, a?, mass?, law?, springs?, rotors?}, "op": ..., ...}`
//! with `op` one of `build`, `evaluate`, `next_angles`, `kink`, `antikink`, `peierls_nabarro`,
//! `modes`, `maxwell_calladine`, `continuum`, `launch`, `propagate`, `scatter` (the fields of each
//! below).

use std::io::Read;

use rotor_chain::ChainGeometry;
use rotor_chain::Potential;
use rotor_chain::SpringNetwork;
use rotor_chain::Stiffness;
use rotor_chain::dynamics::integrate::State;
use rotor_chain::dynamics::launch::{Direction, launch};
use rotor_chain::dynamics::run::{ABSORBING_ENDS, Method, RunOptions, propagate};
use rotor_chain::dynamics::scatter::{ScatterSetup, scatter};
use rotor_chain::statics::antikink::{AntikinkOptions, antikink_at, antikink_relaxed, peierls_nabarro};
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::counting::maxwell_calladine;
use rotor_chain::statics::kink::kink;
use rotor_chain::statics::modes::{ModeOptions, modes};
use rotor_chain::statics::walls::Charge;
use rotor_chain::{Law, RuntimeChain};
use serde::Deserialize;
use serde_json::{Value, json};

#[derive(Deserialize)]
struct ChainSpec {
    n: usize,
    #[serde(deserialize_with = "float")]
    r: f64,
    #[serde(deserialize_with = "float")]
    k: f64,
    #[serde(deserialize_with = "float")]
    theta_bar: f64,
    #[serde(default = "one", deserialize_with = "float")]
    a: f64,
    #[serde(default = "one", deserialize_with = "float")]
    mass: f64,
    #[serde(default)]
    law: Option<String>,
    #[serde(default)]
    springs: Vec<(usize, Option<f64>, Option<f64>)>,
    #[serde(default)]
    rotors: Vec<(usize, f64)>,
}

fn one() -> f64 {
    1.0
}

/// A number, or `"nan"`, `"inf"`, `"-inf"` (JSON has no non-finite numbers; the tests send
/// these as strings).
fn float<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Float {
        Number(f64),
        Text(String),
    }
    match Float::deserialize(d)? {
        Float::Number(x) => Ok(x),
        Float::Text(t) => t.parse().map_err(|_| serde::de::Error::custom(format!("`{t}` is not a number"))),
    }
}

#[derive(Deserialize)]
#[serde(tag = "op", rename_all = "snake_case")]
enum Op {
    Build,
    Evaluate {
        theta: Vec<f64>,
    },
    NextAngles {
        p: usize,
        theta_p: f64,
    },
    Kink {
        centre: f64,
    },
    Antikink {
        centre: f64,
        relaxed: bool,
    },
    PeierlsNabarro,
    Modes {
        theta: Vec<f64>,
        count: Option<usize>,
    },
    MaxwellCalladine {
        theta: Vec<f64>,
    },
    Continuum,
    Launch {
        defect: String,
        position: f64,
        v0: f64,
        direction: String,
    },
    Propagate {
        theta: Vec<f64>,
        omega: Vec<f64>,
        t_max: f64,
        method: String,
        damping: f64,
        absorbing_ends: bool,
    },
    Scatter {
        defect: String,
        v0: f64,
        impurity: usize,
        method: String,
        absorbing_ends: bool,
    },
}

#[derive(Deserialize)]
struct Case {
    chain: ChainSpec,
    #[serde(flatten)]
    op: Op,
}

fn build(s: &ChainSpec) -> Result<RuntimeChain, String> {
    let law = match s.law.as_deref() {
        None | Some("harmonic") => Law::Harmonic,
        Some("quartic") => Law::Quartic,
        Some(other) => return Err(format!("unknown law {other}")),
    };
    let mut b = RuntimeChain::builder(s.n, s.r, s.k, s.theta_bar).lattice_spacing(s.a).mass(s.mass).law(law);
    for &(p, k, l0) in &s.springs {
        b = b.spring(p, k, l0);
    }
    for &(i, r) in &s.rotors {
        b = b.rotor(i, r);
    }
    b.build().map_err(|e| e.to_string())
}

fn charge(name: &str) -> Charge {
    if name == "kink" { Charge::Kink } else { Charge::Antikink }
}

fn charge_name(c: Charge) -> &'static str {
    match c {
        Charge::Kink => "kink",
        Charge::Antikink => "antikink",
    }
}

fn method(name: &str) -> Method {
    if name == "dop853" { Method::dop853() } else { Method::Verlet }
}

fn banded(c: &RuntimeChain, theta: &[f64], f: impl Fn(&RuntimeChain, &[f64], &mut [f64])) -> Value {
    let n = c.rotor_count();
    let mut values = vec![0.0; 2 * n - 1];
    f(c, theta, &mut values);
    let (d, o) = values.split_at(n);
    json!({"diag": d, "off": o})
}

fn run_json(run: &rotor_chain::dynamics::run::Run) -> Value {
    let walls: Vec<Vec<(f64, &str)>> = run
        .tracker
        .snapshots
        .iter()
        .map(|s| s.walls.iter().map(|w| (w.position, charge_name(w.charge))).collect())
        .collect();
    json!({
        "times": run.kinetic.iter().map(|k| k.0).collect::<Vec<_>>(),
        "kinetic": run.kinetic.iter().map(|k| k.1).collect::<Vec<_>>(),
        "walls": walls,
        "theta": run.final_state.theta,
        "omega": run.final_state.omega,
        "time": run.final_state.time,
        "energy_initial": run.report.energy_initial,
        "energy_final": run.report.energy_final,
        "relative_energy_error": run.report.relative_energy_error(),
        "steps": run.report.steps,
        "integrator": run.integrator,
    })
}

fn compute(case: &Case) -> Result<Value, String> {
    let c = build(&case.chain)?;
    let n = c.rotor_count();
    let s = |e: &dyn std::fmt::Display| e.to_string();
    Ok(match &case.op {
        Op::Build => json!({"n": n}),
        Op::Evaluate { theta } => {
            let mut g = vec![0.0; n];
            c.gradient_into(theta, &mut g);
            let mut eg = vec![0.0; n];
            let e2 = c.energy_and_gradient_into(theta, &mut eg);
            let m = n - 1;
            let (mut l, mut t, mut c_values) = (vec![0.0; m], vec![0.0; m], vec![0.0; 2 * m]);
            c.spring_lengths_into(theta, &mut l);
            c.tensions_into(theta, &mut t);
            c.compatibility_into(theta, &mut c_values);
            let (cl, cr) = c_values.split_at(m);
            json!({
                "energy": c.energy(theta),
                "gradient": g,
                "energy_fused": e2,
                "gradient_fused": eg,
                "stiffness": banded(&c, theta, |c, t, v| c.tangent_stiffness_into(t, v)),
                "material": banded(&c, theta, |c, t, v| c.material_stiffness_into(t, v)),
                "stress": banded(&c, theta, |c, t, v| c.stress_matrix_into(t, v)),
                "spring_lengths": l,
                "tensions": t,
                "compatibility": {"left": cl, "right": cr},
            })
        }
        Op::NextAngles { p, theta_p } => {
            let next = c.next_angles(*p, *theta_p).map_err(|e| s(&e))?;
            let previous = c.previous_angles(*p, *theta_p).map_err(|e| s(&e))?;
            json!({"next": next, "previous": previous})
        }
        Op::Kink { centre } => json!({"theta": kink(&c, *centre).map_err(|e| s(&e))?}),
        Op::Antikink { centre, relaxed } => {
            let o = AntikinkOptions::default();
            let a = if *relaxed { antikink_relaxed(&c, *centre, &o) } else { antikink_at(&c, *centre, &o) };
            let a = a.map_err(|e| s(&e))?;
            json!({"theta": a.theta, "energy": a.energy, "centre": a.centre, "index": a.classification.index})
        }
        Op::PeierlsNabarro => {
            let pn = peierls_nabarro(&c, &AntikinkOptions::default()).map_err(|e| s(&e))?;
            json!({
                "minimum_energy": pn.minimum().map_err(|e| s(&e))?.energy,
                "saddle_energy": pn.saddle().map_err(|e| s(&e))?.energy,
                "barrier": pn.barrier,
                "resolved": pn.resolved,
                "minimum_theta": pn.minimum().map_err(|e| s(&e))?.theta,
                "saddle_theta": pn.saddle().map_err(|e| s(&e))?.theta,
            })
        }
        Op::Modes { theta, count } => {
            let found = modes(&c, theta, &ModeOptions { count: *count, ..ModeOptions::default() })
                .map_err(|e| s(&e))?;
            json!({
                "frequencies": found.iter().map(|m| m.frequency).collect::<Vec<_>>(),
                "omega_squared": found.iter().map(|m| m.omega_squared).collect::<Vec<_>>(),
                "vectors": found.iter().map(|m| m.shape.clone()).collect::<Vec<_>>(),
            })
        }
        Op::MaxwellCalladine { theta } => {
            let m = maxwell_calladine(&c, theta, None).map_err(|e| s(&e))?;
            json!({
                "rank": m.rank,
                "zero_modes": m.zero_modes.len(),
                "self_stresses": m.self_stresses.len(),
                "singular_values": m.singular_values,
            })
        }
        Op::Continuum => {
            let s0 = &case.chain;
            let k = ContinuumChain::new(s0.a, s0.r, s0.theta_bar, s0.k, s0.mass).map_err(|e| s(&e))?;
            json!({"antikink_energy": k.antikink_energy(), "width": k.width(), "sound_speed": k.sound_speed()})
        }
        Op::Launch { defect, position, v0, direction } => {
            let d = if direction == "right" { Direction::Right } else { Direction::Left };
            let l = launch(&c, charge(defect), *position, *v0, d).map_err(|e| s(&e))?;
            json!({"theta": l.state.theta, "omega": l.state.omega, "mode": l.mode, "position": l.position})
        }
        Op::Propagate { theta, omega, t_max, method: m, damping, absorbing_ends } => {
            let options = RunOptions {
                t_max: *t_max,
                method: method(m),
                damping: *damping,
                absorbing_ends: absorbing_ends.then_some(ABSORBING_ENDS),
                ..RunOptions::default()
            };
            let state = State { time: 0.0, theta: theta.clone(), omega: omega.clone() };
            let run = propagate(&c, state, &options, &mut |_| false).map_err(|e| s(&e))?;
            run_json(&run)
        }
        Op::Scatter { defect, v0, impurity, method: m, absorbing_ends } => {
            let mut setup = ScatterSetup::from_the_right(charge(defect), *v0, *impurity);
            setup.run.method = method(m);
            setup.run.absorbing_ends = absorbing_ends.then_some(ABSORBING_ENDS);
            let r = scatter(&c, &setup).map_err(|e| s(&e))?;
            json!({
                "outcome": r.outcome.name(),
                "decided_at": r.decided_at,
                "confirmed": r.confirmed,
                "later": r.later.map(|(e, _)| e.name()),
                "later_at": r.later.map(|(_, t)| t),
                "run": run_json(&r.run),
            })
        }
    })
}

fn main() -> std::process::ExitCode {
    let mut input = String::new();
    if let Err(e) = std::io::stdin().read_to_string(&mut input) {
        eprintln!("rotor-chain-reference: cannot read stdin: {e}");
        return std::process::ExitCode::from(2);
    }
    let cases: Vec<Case> = match serde_json::from_str(&input) {
        Ok(cases) => cases,
        Err(e) => {
            eprintln!("rotor-chain-reference: the cases are not valid: {e}");
            return std::process::ExitCode::from(2);
        }
    };
    let results: Vec<Value> = cases
        .iter()
        .map(|case| match compute(case) {
            Ok(v) => json!({"ok": v}),
            Err(e) => json!({"error": e}),
        })
        .collect();
    println!("{}", Value::Array(results));
    std::process::ExitCode::SUCCESS
}
