//! The example models and studies of Lin (2005): the Appendix A beam with the ch. 6.2, 7.1 and
//! 8.5 studies, and the Appendix B slab; the `flowmbd-reduce` studies `lin-beam`
//! ([`beam_study`]) and `lin-slab` ([`slab_study`]) on them.

pub mod beam;
pub mod beam_study;
pub mod slab;
pub mod slab_sim;
pub mod slab_sim3;
pub mod slab_study;
