/* Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
 *
 * The MPI transport of `mjformation sweep`, a module (libmjf_sweep_mpi.so) that the
 * runner dlopen()s only when it runs under mpirun: the mjformation executable itself never
 * links MPI. Every rank plans the same sweep from the same command line; rank 0 keeps the work
 * queue (a run index per request) and receives every result; the other ranks run simulations.
 * With a single rank, rank 0 runs everything itself. */
#ifndef MJFORMATION_APP_SWEEP_MPI_H_
#define MJFORMATION_APP_SWEEP_MPI_H_

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mjfMpiSweep_ {
  void* user;
  /* Rank 0, once MPI runs: prepares the output (folders, resume) and lists the run indices to
   * do in *todo / *n_todo (valid until the sweep ends). Returns 0, or nonzero with a message in
   * error[0..error_size): then no rank runs anything. */
  int (*prepare)(void* user, const int** todo, int* n_todo, char* error, int error_size);
  /* Runs index i on this rank and returns its outcome as text (owned by the caller of run until
   * the next call of run on this rank). */
  const char* (*run)(void* user, int index);
  /* Rank 0: the outcome of index i (text from `run` on some rank). */
  void (*collect)(void* user, int index, const char* outcome);
  /* Rank 0: nonzero once no new run should start (interrupt). */
  int (*stop_requested)(void* user);
} mjfMpiSweep;

/* Initialises MPI (if not yet), fills *rank and *size, runs the sweep and finalises MPI.
 * Returns 0, or nonzero with a message in error[0..error_size). Symbol: mjf_mpi_sweep. */
int mjf_mpi_sweep(mjfMpiSweep* sweep, int* rank, int* size, char* error, int error_size);
typedef int (*mjfMpiSweepFn)(mjfMpiSweep*, int*, int*, char*, int);

#ifdef __cplusplus
}
#endif

#endif /* MJFORMATION_APP_SWEEP_MPI_H_ */
