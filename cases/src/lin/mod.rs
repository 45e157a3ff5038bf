//! The example models and studies of Lin (2005): the Appendix A beam with the ch. 6.2, 7.1 and
//! 8.5 studies, and the Appendix B slab.

pub mod beam;
pub mod slab;
pub mod slab_sim;
pub mod slab_sim3;
