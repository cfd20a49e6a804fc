//! Linear algebra on the chain's banded matrices (symmetric tridiagonal): spectra, lowest modes,
//! Sturm counts and solves in O(n) to O(n^2), where a dense decomposition would cost O(n^3).
