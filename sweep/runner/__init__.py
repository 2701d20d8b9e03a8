"""Running simulations: one scene, and studies as grids of cells dealt in chunks to MPI ranks.

Studies have part files, resume, merge, bisection of boundaries (refine) and progress."""
