// The explicit list of backends (style.md: PETSc's PCRegisterAll, libCEED's X-macro list).
// Adding a backend: one new file defining `make_<id>(MPI_Comm)` plus one line here.
//   STICTION_BACKEND(id, "name", "one-line description", "PETSc external package or empty")
STICTION_BACKEND(lu_mumps, "lu-mumps", "global LU factorisation by MUMPS (the paper's GlobalLU)", "mumps")
