// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The MPI transport of `mjformation sweep` (sweep_mpi.h): rank 0 hands out run indices one at a
// time (a work queue: fast and slow runs balance themselves) and receives every outcome; ranks
// 1..K-1 run simulations. Only this module links MPI; the runner dlopen()s it under mpirun.
#include "mjformation/app/sweep_mpi.h"

#include <mpi.h>
#include <time.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr int kTagReady = 1;  // worker -> 0: "<index>\n<outcome>" (index -1: first request)
constexpr int kTagWork = 2;   // 0 -> worker: an index, or -1: no more work

void Nap() {
  // Rank 0 polls instead of blocking in MPI_Recv: Open MPI busy-waits there, which would take a
  // core from the simulations on an oversubscribed machine.
  timespec t{0, 1000000};  // 1 ms
  nanosleep(&t, nullptr);
}

int Dispatch(mjfMpiSweep* s, int size, char* error, int error_size) {
  const int* todo = nullptr;
  int n_todo = 0;
  const int prepared = s->prepare(s->user, &todo, &n_todo, error, error_size);
  int next = 0;
  if (size == 1) {  // a single rank runs everything itself
    for (; prepared == 0 && next < n_todo && !s->stop_requested(s->user); ++next) {
      s->collect(s->user, todo[next], s->run(s->user, todo[next]));
    }
    return prepared;
  }
  int active = size - 1;
  std::vector<char> buffer;
  while (active > 0) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagReady, MPI_COMM_WORLD, &flag, &status);
    if (!flag) {
      Nap();
      continue;
    }
    int count = 0;
    MPI_Get_count(&status, MPI_CHAR, &count);
    buffer.assign(static_cast<size_t>(count) + 1, '\0');
    MPI_Recv(buffer.data(), count, MPI_CHAR, status.MPI_SOURCE, kTagReady, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    const int finished = std::atoi(buffer.data());
    if (finished >= 0) s->collect(s->user, finished, std::strchr(buffer.data(), '\n') + 1);
    int work = -1;
    if (prepared == 0 && next < n_todo && !s->stop_requested(s->user)) work = todo[next++];
    MPI_Send(&work, 1, MPI_INT, status.MPI_SOURCE, kTagWork, MPI_COMM_WORLD);
    if (work < 0) --active;
  }
  return prepared;
}

void Work(mjfMpiSweep* s) {
  std::string message = "-1\n";
  while (true) {
    MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kTagReady,
             MPI_COMM_WORLD);
    int work = -1;
    MPI_Recv(&work, 1, MPI_INT, 0, kTagWork, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (work < 0) return;
    message = std::to_string(work) + "\n" + s->run(s->user, work);
  }
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int mjf_mpi_sweep(mjfMpiSweep* s, int* rank,
                                                                    int* size, char* error,
                                                                    int error_size) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) MPI_Init(nullptr, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  int rc = 0;
  if (*rank == 0) {
    rc = Dispatch(s, *size, error, error_size);
  } else {
    Work(s);
  }
  // Rank 0's verdict (e.g. the output folder cannot be written) for every rank.
  MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (rc != 0 && *rank != 0) std::snprintf(error, error_size, "rank 0 could not start the sweep");
  MPI_Finalize();
  return rc;
}
