// The explicit list of backends (style.md: PETSc's PCRegisterAll, libCEED's X-macro list).
// Adding a backend: one new file defining `make_<id>(MPI_Comm)` plus one line here.
//   STICTION_BACKEND(id, "name", "one-line description", "PETSc external package or empty", processes)
// processes: kAnyProcesses when the backend runs on a distributed system, kOneProcess when
// its package is sequential (UMFPACK). On several processes the Schur backends sweep A_qq
// and alpha M_p process by process and factor the contact level's S~ by MUMPS.
STICTION_BACKEND(lu_mumps, "lu-mumps", "global LU factorisation by MUMPS (the paper's GlobalLU)", "mumps", kAnyProcesses)
STICTION_BACKEND(lu_mumps_blr, "lu-mumps-blr", "GMRES with a block low-rank MUMPS factorisation (compression tolerance -lu_mumps_blr_mat_mumps_cntl_7)", "mumps", kAnyProcesses)
STICTION_BACKEND(lu_umfpack, "lu-umfpack", "global LU factorisation by SuiteSparse UMFPACK (second direct solver)", "suitesparse", kOneProcess)
STICTION_BACKEND(ilu_gmres, "ilu-gmres", "GMRES with ILU(k) of the whole system (k = -ilu_gmres_pc_factor_levels, default 0)", "", kAnyProcesses)
STICTION_BACKEND(boomeramg, "boomeramg", "GMRES with one BoomerAMG V-cycle on the whole system (naive AMG)", "hypre", kAnyProcesses)
STICTION_BACKEND(gamg, "gamg", "GMRES with one PETSc GAMG V-cycle (smoothed aggregation, rigid-body modes); no pressure or contact block", "", kAnyProcesses)
STICTION_BACKEND(schur_lu, "schur-lu", "GMRES with the paper's HP (10): direct solve of A_ll, one SSOR sweep on A_qq", "mumps", kAnyProcesses)
STICTION_BACKEND(schur_amg, "schur-amg", "GMRES with HP (10): one BoomerAMG V-cycle on A_ll, one SSOR sweep on A_qq", "hypre", kAnyProcesses)
STICTION_BACKEND(schur_gamg, "schur-gamg", "GMRES with HP (10): one PETSc GAMG V-cycle on A_ll, one SSOR sweep on A_qq", "", kAnyProcesses)
STICTION_BACKEND(fieldsplit_schur, "fieldsplit-schur", "GMRES with PETSc's Schur field split: GAMG on the displacement, selfp on the pressure/contact block", "mumps", kAnyProcesses)
