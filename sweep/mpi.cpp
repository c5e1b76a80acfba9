// A sweep across MPI ranks (`mpirun -np N masonry sweep ...`). Rank 0 reads the files and the
// table so far and broadcasts the texts and the to-do list; runs go to ranks by their position in
// that list modulo the size (static, so the split does not depend on timing); every rank sends
// its rows to rank 0 as they finish, and rank 0 appends them and writes the table and the report.
// Only the main thread of a rank calls MPI (MPI_THREAD_FUNNELED).
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>

#include "sweep/runner.hpp"

namespace masonry {

using nlohmann::json;

namespace {

constexpr int kRowTag = 1;   // a finished row (JSON text)
constexpr int kDoneTag = 2;  // the sending rank has sent all its rows

// MPI_Init on construction, MPI_Finalize on destruction, so every way out of the sweep finalises.
struct MpiSession {
  int rank = 0, size = 1;
  MpiSession() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    if (provided < MPI_THREAD_FUNNELED) {
      std::fprintf(stderr, "masonry sweep: the MPI library does not allow threads beside MPI (MPI_THREAD_FUNNELED)\n");
      MPI_Abort(MPI_COMM_WORLD, 2);
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
  }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

void broadcast(std::string& s) {
  long long n = static_cast<long long>(s.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  s.resize(static_cast<size_t>(n));
  MPI_Bcast(s.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
}

void send(const std::string& s, int tag) { MPI_Send(s.data(), static_cast<int>(s.size()), MPI_CHAR, 0, tag, MPI_COMM_WORLD); }

}  // namespace

bool started_by_mpirun() {
  // Open MPI's mpirun (and PMIx launchers) set these for every process they start. A plain
  // `masonry sweep` must not initialise MPI: a singleton start is slow and fragile in containers.
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr;
}

int run_sweep_mpi(const std::string& spec_path, const SweepOptions& o) {
  MpiSession mpi;
  // Rank 0: the inputs and the to-do list, or the error that stops every rank.
  std::string msg;
  sweep_detail::Prepared pr;
  if (mpi.rank == 0) {
    try {
      const SweepInput in = read_sweep_input(spec_path);
      pr = sweep_detail::prepare(in, o);
      msg = json{{"spec", in.spec_text}, {"spec_source", in.spec_source}, {"case", in.case_text}, {"case_source", in.case_source}, {"todo", pr.todo}}
                .dump();
    } catch (const std::exception& e) {
      msg = json{{"error", e.what()}}.dump();
    }
  }
  broadcast(msg);
  const json j = json::parse(msg);
  if (j.contains("error")) {
    if (mpi.rank == 0) throw SweepError(j["error"].get<std::string>());
    return 2;
  }
  const std::vector<int> todo = j["todo"].get<std::vector<int>>();
  if (mpi.rank != 0) {
    try {
      pr.plan = plan_sweep(SweepInput{j["spec"].get<std::string>(), j["spec_source"].get<std::string>(), j["case"].get<std::string>(),
                                      j["case_source"].get<std::string>()});
    } catch (const std::exception& e) {
      std::fprintf(stderr, "masonry sweep: rank %d: %s\n", mpi.rank, e.what());
      MPI_Abort(MPI_COMM_WORLD, 2);
    }
  }
  std::vector<int> mine;
  for (size_t k = 0; k < todo.size(); ++k)
    if (static_cast<int>(k % static_cast<size_t>(mpi.size)) == mpi.rank) mine.push_back(todo[k]);
  // One run at a time per rank unless --jobs: mpirun places a rank per core.
  const int jobs = o.jobs > 0 ? o.jobs : 1;
  if (mpi.rank != 0) {
    sweep_detail::execute_runs(pr.plan, mine, jobs, o.keep_runs, [](const SweepRow& r) { send(row_to_json(r).dump(), kRowTag); }, {});
    send("", kDoneTag);
    return 0;
  }
  try {
    sweep_detail::Recorder record(
        pr, o, mpi.size, std::string(mpi.size == 1 ? "MPI rank" : "MPI ranks") + (jobs > 1 ? " x " + std::to_string(jobs) + " threads" : ""));
    int finished_ranks = 0;
    // Rows from other ranks, taken whenever this rank is between its own rows. Iprobe and a short
    // sleep rather than a blocking receive, which in Open MPI spins and would take a core from
    // the runs.
    const auto poll = [&] {
      for (;;) {
        int flag = 0;
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
        if (!flag) return;
        int n = 0;
        MPI_Get_count(&st, MPI_CHAR, &n);
        std::string buf(static_cast<size_t>(n), '\0');
        MPI_Recv(buf.data(), n, MPI_CHAR, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (st.MPI_TAG == kDoneTag)
          ++finished_ranks;
        else
          record(row_from_json(json::parse(buf)));
      }
    };
    sweep_detail::execute_runs(pr.plan, mine, jobs, o.keep_runs, std::ref(record), poll);
    for (poll(); finished_ranks < mpi.size - 1; poll()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return record.finish();
  } catch (const std::exception& e) {
    // The other ranks may still be sending: stop them all rather than leave them waiting.
    std::fprintf(stderr, "masonry sweep: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  return 2;
}

}  // namespace masonry
