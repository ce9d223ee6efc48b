//! End-to-end tests of the `subcount` binary.

mod budget;
mod compositions;
mod creases;
mod descriptor;
mod files;
mod hostile;
mod hostile3;
mod hostile_dual;
mod level_zero;
mod limit;
mod matrix;
mod meshes;
mod plot;
mod schemes;
mod tags;
mod util;
mod uv_counts;
mod uv_input;
mod uv_subdivide;
