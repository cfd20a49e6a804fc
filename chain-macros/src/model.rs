//! Phase 3: the chain in symbols. Parameters become graph nodes (literals fold into constants,
//! fields become symbols named by the Rust expression that reads them, `self.k_imp`), the spring
//! law is the default harmonic one or the user's, and `chain-symbolic` derives everything else.

use chain_geometry as geo;
use chain_symbolic::chain::{ChainOutputs, Kernel};
use chain_symbolic::lower::{Schedule, lower_with};
use chain_symbolic::{Float, Graph, Id, Node, SpringLaw, SpringParams};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use crate::attr::Value;
use crate::valid::{Model, Uniform};

/// The hidden path through which generated code reaches its support items.
pub const PRIVATE: &str = "::rotor_chain::__private";

/// The path prefix of `float`'s math functions in rendered source: `math::` for `f64`,
/// `math::single::` for `f32`.
pub fn math_prefix(float: Float) -> String {
    match float {
        Float::F64 => format!("{PRIVATE}::math::"),
        Float::F32 => format!("{PRIVATE}::math::single::"),
    }
}

/// The float type as a Rust type.
pub fn float_type(float: Float) -> TokenStream {
    let ty = format_ident!("{}", float.name());
    quote!(#ty)
}

/// The graph node of a parameter value.
pub fn value_node(g: &mut Graph, v: &Value) -> Id {
    match v {
        Value::Literal { value, .. } => g.constant(*value),
        Value::Field(ident) => g.symbol(&format!("self.{ident}")),
    }
}

/// The Rust expression of a parameter value, in the chain's float type (literals were rounded to
/// it in validation, fields are declared in it).
pub fn value_tokens(v: &Value, float: Float) -> TokenStream {
    match v {
        Value::Literal { value, .. } => float_tokens(*value, float),
        Value::Field(ident) => quote!(self.#ident),
    }
}

/// The Rust expression of a parameter value as an `f64` (`f64::from(self.k)` for a field of an
/// `f32` chain): for the rules of `chain-geometry`, which are checked in `f64`.
pub fn value_tokens_f64(v: &Value, float: Float) -> TokenStream {
    match (v, float) {
        (Value::Literal { value, .. }, _) => float_tokens(*value, Float::F64),
        (Value::Field(ident), Float::F64) => quote!(self.#ident),
        (Value::Field(ident), Float::F32) => quote!(::core::primitive::f64::from(self.#ident)),
    }
}

/// A computed constant as a Rust expression of type `float`, rounded to it (`f64::INFINITY` and
/// `f64::NAN` where a literal cannot be written: parameters near `f64::MAX` can overflow the rest
/// length).
fn float_tokens(x: f64, float: Float) -> TokenStream {
    float.render_const(x).parse().unwrap_or_else(|_| quote!(::core::primitive::f64::NAN))
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

    /// A parameter value as a Rust expression of the chain's float type.
    pub fn value(&self, v: &Value) -> TokenStream {
        value_tokens(v, self.float)
    }

    /// The default rest length as a Rust expression of the chain's float type. An `f32` chain
    /// whose rest length depends on fields computes it in `f32`, from the graph node the energy
    /// uses (so the branch solve and the energy share it, and no `f64` routine is linked).
    pub fn rest_length_tokens(&self) -> TokenStream {
        let p: TokenStream = PRIVATE.parse().expect("path");
        match (&self.uniform, self.float) {
            (Uniform::RestLength(v), _) => self.value(v),
            (Uniform::ThetaBar(tb), float) => match (self.literal_geometry(), tb.literal()) {
                (Some((a, r)), Some(t)) => float_tokens(geo::rest_length(a, r, t), float),
                _ if float == Float::F32 => self.rest_length_program(),
                _ => {
                    let (a, r, t) = (self.value(&self.a), self.value(&self.r), self.value(tb));
                    quote!(#p::geometry::rest_length(#a, #r, #t))
                }
            },
        }
    }

    /// The rest length node lowered to a block of the chain's float type.
    fn rest_length_program(&self) -> TokenStream {
        let mut g = Graph::new();
        let lbar = self.rest_length_node(&mut g);
        let leaf = |id: Id| match g.node(id) {
            Node::Symbol(s) => Some(g.symbol_name(s).to_owned()),
            _ => None,
        };
        let program = lower_with(&g, &[lbar], &leaf, Schedule::DepthFirst).expect("every symbol is a field");
        let ty = self.float.name();
        let steps = program.render_into("l", self.float, &math_prefix(self.float), &["lbar".to_owned()]);
        format!("{{\nlet mut lbar: {ty};\n{steps}lbar\n}}").parse().expect("rest length source parses")
    }

    /// `theta_bar` as a Rust expression of the chain's float type. For a rest length read from a
    /// field that admits no uniform state the expression is NaN; `check()` reports that case as an
    /// error.
    pub fn theta_bar_tokens(&self) -> TokenStream {
        let p: TokenStream = PRIVATE.parse().expect("path");
        let ty = float_type(self.float);
        match &self.uniform {
            Uniform::ThetaBar(tb) => self.value(tb),
            Uniform::RestLength(rl) => match (self.literal_geometry(), rl.literal()) {
                (Some((a, r)), Some(l)) => {
                    float_tokens(geo::theta_bar_from_rest_length(a, r, l).expect("validated"), self.float)
                }
                _ => {
                    let f = |v| value_tokens_f64(v, self.float);
                    let (a, r, l) = (f(&self.a), f(&self.r), f(rl));
                    let theta_bar = quote!(#p::geometry::theta_bar_from_rest_length(#a, #r, #l));
                    match self.float {
                        Float::F64 => quote!(#theta_bar.unwrap_or(f64::NAN)),
                        Float::F32 => quote!(#theta_bar.map_or(#ty::NAN, |theta_bar| theta_bar as #ty)),
                    }
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
