#pragma once
// A task farm on MPI (parallel/task_farm.hpp): rank 0 is the lead and computes too. Tasks are handed out one at a
// time, as they differ in length by an order of magnitude: a worker asks for a task, sending the result of its last
// one; the lead answers such requests before each of its own tasks and, through `poll`, during them (about every
// 1024 steps of a vault study, a few milliseconds apart), so that no worker waits for a lead's task to end. Needs
// <mpi.h>: include it only in programs built with MPI.

#ifndef OMPI_SKIP_MPICXX
#define OMPI_SKIP_MPICXX 1  // the C interface only: no deprecated C++ bindings
#endif
#ifndef MPICH_SKIP_MPICXX
#define MPICH_SKIP_MPICXX 1
#endif
#include <mpi.h>

#include <chrono>
#include <cstddef>
#include <string>
#include <thread>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/parallel/task_farm.hpp"

namespace blockdem::parallel {

class MpiFarm {
 public:
  explicit MpiFarm(MPI_Comm comm = MPI_COMM_WORLD) : comm_(comm) {
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &size_);
  }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool lead() const { return rank_ == 0; }
  /// Wall time the lead spent answering workers (its overhead), s.
  double serve_seconds() const { return serve_seconds_; }

  template <FarmWork Work>
  std::vector<std::string> run(std::size_t tasks, Work&& work) {
    return lead() ? run_lead(tasks, work) : run_worker(work);
  }

 private:
  static constexpr int request_tag = 701, assign_tag = 702;

  template <class Work>
  std::vector<std::string> run_lead(std::size_t tasks, Work& work) {
    using clock = std::chrono::steady_clock;
    std::vector<std::string> out(tasks);
    std::size_t next = 0;
    int active = size_ - 1;
    const Poll serve = [&] {
      const auto start = clock::now();
      for (;;) {
        int flag = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, request_tag, comm_, &flag, &status);
        if (!flag) break;
        int length = 0;
        MPI_Get_count(&status, MPI_CHAR, &length);
        std::string message(static_cast<std::size_t>(length), '\0');
        MPI_Recv(message.data(), length, MPI_CHAR, status.MPI_SOURCE, request_tag, comm_, MPI_STATUS_IGNORE);
        if (!message.empty()) {  // "<task>\n<result>"
          const auto newline = message.find('\n');
          const std::size_t k = std::stoull(message.substr(0, newline));
          if (k < tasks) out[k] = message.substr(newline + 1);
        }
        long long k = next < tasks && !interrupted() ? static_cast<long long>(next++) : -1;
        if (k < 0) --active;
        MPI_Send(&k, 1, MPI_LONG_LONG, status.MPI_SOURCE, assign_tag, comm_);
      }
      serve_seconds_ += std::chrono::duration<double>(clock::now() - start).count();
    };
    for (;;) {
      serve();
      if (next >= tasks || interrupted()) break;
      const std::size_t k = next++;
      out[k] = work(k, serve);
    }
    while (active > 0) {  // the last workers' results; the lead has nothing left to compute
      serve();
      if (active > 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return out;
  }

  template <class Work>
  std::vector<std::string> run_worker(Work& work) {
    std::string message;  // the first request carries no result
    const Poll none;
    for (;;) {
      MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, request_tag, comm_);
      long long k = -1;
      MPI_Recv(&k, 1, MPI_LONG_LONG, 0, assign_tag, comm_, MPI_STATUS_IGNORE);
      if (k < 0) break;
      message = std::to_string(k) + '\n' + work(static_cast<std::size_t>(k), none);
    }
    return {};
  }

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  double serve_seconds_ = 0;
};

}  // namespace blockdem::parallel
