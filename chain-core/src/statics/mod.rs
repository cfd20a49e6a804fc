//! Static linkage analysis (paper Sections II-V, VII and Appendices A, C, D).
