//! # flowing
//!
//! The Eulerian flowing-material layer (Ribaric 2012 ch. 4–8 and App. A): mode-shape derivative
//! operators along a flow coordinate, the travelling string, the flowing-material belt drive and
//! the reduced FE tire whose mesh does not move with the material.
