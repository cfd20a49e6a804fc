//! Phase 3: the chain in symbols. Parameters become graph nodes (literals fold into constants,
//! fields become symbols named by the Rust expression that reads them, `self.k_imp`), the spring
//! law is the default harmonic one or the user's, and `chain-symbolic` derives everything else.

use chain_geometry as geo;
use chain_symbolic::chain::{ChainOutputs, Kernel};
use chain_symbolic::{Graph, Id, SpringLaw, SpringParams};
use proc_macro2::TokenStream;
use quote::quote;

use crate::attr::Value;
use crate::valid::{Model, Uniform};

/// The hidden path through which generated code reaches its support items.
pub const PRIVATE: &str = "::rotor_chain::__private";

/// The math functions' path prefix in rendered source.
pub fn math_prefix() -> String {
    format!("{PRIVATE}::math::")
}

/// The graph node of a parameter value.
pub fn value_node(g: &mut Graph, v: &Value) -> Id {
    match v {
        Value::Literal { value, .. } => g.constant(*value),
        Value::Field(ident) => g.symbol(&format!("self.{ident}")),
    }
}

/// The Rust expression of a parameter value.
pub fn value_tokens(v: &Value) -> TokenStream {
    match v {
        Value::Literal { value, .. } => {
            let lit = proc_macro2::Literal::f64_suffixed(*value);
            quote!(#lit)
        }
        Value::Field(ident) => quote!(self.#ident),
    }
}

/// A computed constant as a Rust expression (`f64::INFINITY` and `f64::NAN` where a literal
/// cannot be written: parameters near `f64::MAX` can overflow the rest length).
fn f64_tokens(x: f64) -> TokenStream {
    chain_symbolic::lower::render_const(x).parse().unwrap_or_else(|_| quote!(::core::primitive::f64::NAN))
}

impl Model {
    /// The law of this chain, built into `g`.
    pub fn spring_law(&self, g: &mut Graph) -> SpringLaw {
        match &self.law {
            Some(law) => law.build(g),
            None => SpringLaw::harmonic(g),
        }
    }

    /// `[a, r, theta_bar]` if all are literals.
    fn literal_geometry(&self) -> Option<(f64, f64)> {
        Some((self.a.literal()?, self.r.literal()?))
    }

    /// The default rest length `lbar` as a graph node (paper Sec. III: `lbar^2 = a^2 + 4 r^2 cos^2 theta_bar`).
    pub fn rest_length_node(&self, g: &mut Graph) -> Id {
        match &self.uniform {
            Uniform::RestLength(v) => value_node(g, v),
            Uniform::ThetaBar(tb) => {
                if let (Some((a, r)), Some(t)) = (self.literal_geometry(), tb.literal()) {
                    return g.constant(geo::rest_length(a, r, t));
                }
                let (a, r, t) = (value_node(g, &self.a), value_node(g, &self.r), value_node(g, tb));
                let a2 = g.powi(a, 2);
                let c = g.cos(t);
                let rc = g.mul(r, c);
                let rc2 = g.powi(rc, 2);
                let four = g.constant(4.0);
                let term = g.mul(four, rc2);
                let sum = g.add(a2, term);
                g.sqrt(sum)
            }
        }
    }

    /// The default rest length as a Rust expression.
    pub fn rest_length_tokens(&self) -> TokenStream {
        let p: TokenStream = PRIVATE.parse().expect("path");
        match &self.uniform {
            Uniform::RestLength(v) => value_tokens(v),
            Uniform::ThetaBar(tb) => match (self.literal_geometry(), tb.literal()) {
                (Some((a, r)), Some(t)) => f64_tokens(geo::rest_length(a, r, t)),
                _ => {
                    let (a, r, t) = (value_tokens(&self.a), value_tokens(&self.r), value_tokens(tb));
                    quote!(#p::geometry::rest_length(#a, #r, #t))
                }
            },
        }
    }

    /// `theta_bar` as a Rust expression. For a rest length read from a field that admits no
    /// uniform state the expression is NaN; `check()` reports that case as an error.
    pub fn theta_bar_tokens(&self) -> TokenStream {
        let p: TokenStream = PRIVATE.parse().expect("path");
        match &self.uniform {
            Uniform::ThetaBar(tb) => value_tokens(tb),
            Uniform::RestLength(rl) => match (self.literal_geometry(), rl.literal()) {
                (Some((a, r)), Some(l)) => {
                    f64_tokens(geo::theta_bar_from_rest_length(a, r, l).expect("validated"))
                }
                _ => {
                    let (a, r, l) = (value_tokens(&self.a), value_tokens(&self.r), value_tokens(rl));
                    quote!(#p::geometry::theta_bar_from_rest_length(#a, #r, #l).unwrap_or(f64::NAN))
                }
            },
        }
    }

    pub fn rotor_length_value(&self, i: usize) -> &Value {
        self.rotors.get(&i).unwrap_or(&self.r)
    }

    /// Spring `p`'s parameters as graph nodes, `lbar` being the default rest length node.
    pub fn spring_params(&self, g: &mut Graph, p: usize, lbar: Id) -> SpringParams {
        let (k, l0) = self.springs.get(&p).cloned().unwrap_or((None, None));
        SpringParams {
            a: value_node(g, &self.a),
            r1: value_node(g, self.rotor_length_value(p)),
            r2: value_node(g, self.rotor_length_value(p + 1)),
            k: value_node(g, k.as_ref().unwrap_or(&self.k)),
            l0: match &l0 {
                Some(v) => value_node(g, v),
                None => lbar,
            },
        }
    }

    /// The unrolled chain: every spring derived with its own parameters in one graph.
    pub fn unrolled_outputs(&self) -> (Graph, ChainOutputs) {
        let mut g = Graph::new();
        let law = self.spring_law(&mut g);
        let lbar = self.rest_length_node(&mut g);
        let springs: Vec<SpringParams> =
            (0..self.springs()).map(|p| self.spring_params(&mut g, p, lbar)).collect();
        let out = ChainOutputs::unrolled(&mut g, &law, &springs, &|g, i| g.symbol(&format!("theta[{i}]")));
        (g, out)
    }

    /// The nodes of one spring's derivation with this chain's law: the code each unrolled spring
    /// adds.
    pub fn spring_cost(&self) -> usize {
        Kernel::new(&|g: &mut Graph| self.spring_law(g)).graph.len()
    }

    /// Rust source of the per-spring kernel for the looped strategy.
    pub fn kernel_source(&self) -> String {
        let kernel = Kernel::new(&|g: &mut Graph| self.spring_law(g));
        kernel.render().expect("the kernel names every symbol")
    }
}
