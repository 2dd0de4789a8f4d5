// RunRanks over MPI (built with THAW_MPI): the leader (rank 0) hands out items (frames, mesh
// chunks) from a dispatcher thread while its main thread works too; other ranks ask for an item,
// work on it, and ask again (a master/worker queue: items differ in cost, so static splits would
// idle), or with `ahead` ask for their next items before they need them. Waiting ranks poll with
// short sleeps instead of MPI's busy-waiting, so a rank that waits (for the leader's simulation,
// say) leaves its core to the ranks that work.
#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <deque>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "base/outcome.h"
#include "src/pipeline/run_ranks.h"

namespace thaw::pipeline {
namespace {

constexpr int kTagAsk = 1;  // worker -> leader: "ready" ('R'), "done" ('D'), failed ('E' + outcome)
constexpr int kTagItem = 2;  // leader -> worker: the next item, or -1: no more
constexpr auto kPoll = std::chrono::milliseconds(1);

// The sleeps between polls grow from 50 us to kPoll: an answer that comes within microseconds (a
// hand-out) is not held for a millisecond (a fixed 1 ms sleep on each side of a hand-out idled
// ranks for longer than a surface takes: docs/benchmarks.md), while a long wait (the leader's
// simulation) still wakes at most about a thousand times a second.
class Backoff {
 public:
  void pause() {
    std::this_thread::sleep_for(m_sleep);
    m_sleep = std::min<std::chrono::microseconds>(2 * m_sleep, kPoll);
  }
  void reset() { m_sleep = kFirst; }

 private:
  static constexpr std::chrono::microseconds kFirst{50};
  std::chrono::microseconds m_sleep = kFirst;
};

void sleepy_wait(MPI_Request& request) {
  int done = 0;
  Backoff backoff;
  for (MPI_Test(&request, &done, MPI_STATUS_IGNORE); !done;
       MPI_Test(&request, &done, MPI_STATUS_IGNORE))
    backoff.pause();
}

class MpiRanks final : public RunRanks {
 public:
  MpiRanks() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_MULTIPLE, &provided);
    // The leader's dispatcher thread calls MPI while its main thread renders (and does not
    // call MPI then): serialized calls from any thread suffice.
    m_threads = provided >= MPI_THREAD_SERIALIZED;
    MPI_Comm_rank(MPI_COMM_WORLD, &m_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &m_size);
  }
  ~MpiRanks() override { MPI_Finalize(); }
  int rank() const override { return m_rank; }
  int size() const override { return m_size; }

  void barrier() override {
    MPI_Request r;
    MPI_Ibarrier(MPI_COMM_WORLD, &r);
    sleepy_wait(r);
  }

  std::string broadcast(const std::string& text) override {
    long n = static_cast<long>(text.size());
    MPI_Request r;
    MPI_Ibcast(&n, 1, MPI_LONG, 0, MPI_COMM_WORLD, &r);
    sleepy_wait(r);
    std::string out = leader() ? text : std::string(static_cast<std::size_t>(n), '\0');
    if (n > 0) {
      MPI_Ibcast(out.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD, &r);
      sleepy_wait(r);
    }
    return out;
  }

  std::vector<std::string> hand_out(const std::vector<long>& items,
                                    const std::function<std::string(long)>& work,
                                    const std::function<void(long)>& done, int ahead) override {
    if (m_size == 1) return RunRanks::hand_out(items, work, done, ahead);
    std::vector<std::string> results(items.size());
    const int depth = 1 + std::max(0, ahead);
    const Outcome failure =
        leader() ? lead(items, work, done, results, depth) : follow(work, depth);
    leaders_outcome(failure).rethrow();  // the leader heard every rank's: its word is the end
    return results;
  }

 protected:
  std::string first_nonempty(const std::string& error) override {
    // Every rank's length, then the texts of the ranks that failed (rank order).
    std::vector<int> lengths(static_cast<std::size_t>(m_size));
    int mine = static_cast<int>(error.size());
    MPI_Request r;
    MPI_Iallgather(&mine, 1, MPI_INT, lengths.data(), 1, MPI_INT, MPI_COMM_WORLD, &r);
    sleepy_wait(r);
    std::vector<int> offsets(lengths.size(), 0);
    for (std::size_t i = 1; i < lengths.size(); ++i) offsets[i] = offsets[i - 1] + lengths[i - 1];
    std::string all(static_cast<std::size_t>(offsets.back() + lengths.back()), '\0');
    if (all.empty()) return "";
    std::string sent = error;  // MPI wants a non-const buffer
    MPI_Iallgatherv(sent.data(), mine, MPI_CHAR, all.data(), lengths.data(), offsets.data(),
                    MPI_CHAR, MPI_COMM_WORLD, &r);
    sleepy_wait(r);
    for (std::size_t i = 0; i < lengths.size(); ++i)
      if (lengths[i] > 0)
        return all.substr(static_cast<std::size_t>(offsets[i]),
                          static_cast<std::size_t>(lengths[i]));
    return "";
  }

 private:
  /// How the work on `item` ended, and its text.
  static std::pair<Outcome, std::string> attempt(const std::function<std::string(long)>& work,
                                                 long item) {
    std::string text;
    const Outcome outcome = Outcome::of([&] { text = work(item); });
    return {outcome, std::move(text)};
  }

  /// The first failure on any rank (ok if none).
  Outcome lead(const std::vector<long>& items, const std::function<std::string(long)>& work,
               const std::function<void(long)>& done, std::vector<std::string>& results,
               int depth) {
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::mutex mutex, done_mutex;
    Outcome first_failure;
    const auto fail = [&](const Outcome& e) {
      std::lock_guard<std::mutex> lock(mutex);
      if (first_failure.ok()) first_failure = e;
      failed = true;
    };
    const auto take = [&]() -> long {  // an index into items, or -1
      if (failed) return -1;
      const std::size_t i = next++;
      return i < items.size() ? static_cast<long>(i) : -1;
    };
    const auto finish = [&](long index) {
      std::lock_guard<std::mutex> lock(done_mutex);  // done() is never called concurrently
      if (done) done(index);
    };
    // Items not yet taken by anyone.
    const auto left = [&]() -> std::size_t {
      const std::size_t taken = next;
      return taken < items.size() ? items.size() - taken : 0;
    };
    const auto dispatch = [&] {
      // The indexes each worker holds, oldest first: its "done" message carries the oldest's
      // text. Every message is answered; a worker has `depth` requests open until it has been
      // answered "no more" that many times, and sends nothing after.
      std::vector<std::deque<long>> busy(static_cast<std::size_t>(m_size));
      std::vector<int> ends(static_cast<std::size_t>(m_size), 0);
      // Requests held back: a worker that asked ahead while it has work in hand is not given one
      // of the last items (fewer than ranks): whichever rank is free first takes it, rather than
      // it waiting behind that worker's current item while another rank idles. Answered once the
      // worker's item is done, or with "no more" once nothing is left.
      std::vector<int> held(static_cast<std::size_t>(m_size), 0);
      const auto answer = [&](std::size_t source) {
        const long index = take();
        const long item = index < 0 ? -1 : items[static_cast<std::size_t>(index)];
        if (index >= 0) busy[source].push_back(index);
        MPI_Send(&item, 1, MPI_LONG, static_cast<int>(source), kTagItem, MPI_COMM_WORLD);
        return item < 0 && ++ends[source] == depth;  // this worker asks no more
      };
      const auto hold = [&](std::size_t source) {
        return !busy[source].empty() && !failed && left() > 0 &&
               left() < static_cast<std::size_t>(m_size);
      };
      Backoff backoff;
      for (int active = m_size - 1; active > 0;) {
        for (std::size_t source = 1; source < held.size(); ++source)
          if (held[source] > 0 && !hold(source)) {
            --held[source];
            if (answer(source)) --active;
          }
        int flag = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, kTagAsk, MPI_COMM_WORLD, &flag, &status);
        if (!flag) {
          backoff.pause();
          continue;
        }
        backoff.reset();
        int length = 0;
        MPI_Get_count(&status, MPI_CHAR, &length);
        std::string message(static_cast<std::size_t>(length), '\0');
        MPI_Recv(message.data(), length, MPI_CHAR, status.MPI_SOURCE, kTagAsk, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
        const auto source = static_cast<std::size_t>(status.MPI_SOURCE);
        if (message[0] == 'D' || message[0] == 'E') {
          const long index = busy[source].front();
          busy[source].pop_front();
          if (message[0] == 'D') {
            results[static_cast<std::size_t>(index)] = message.substr(1);
            finish(index);
          } else {
            fail(Outcome::from_text(message.substr(1)));
          }
        }
        // Answers go out in the order asked (a held request first): they are all alike.
        if (held[source] > 0 && !hold(source)) {
          --held[source];
          if (answer(source)) --active;
        }
        if (hold(source))
          ++held[source];
        else if (answer(source))
          --active;
      }
    };
    if (m_threads) {
      std::thread dispatcher(dispatch);
      for (long index = take(); index >= 0; index = take()) {
        auto [e, text] = attempt(work, items[static_cast<std::size_t>(index)]);
        if (e.ok()) {
          results[static_cast<std::size_t>(index)] = std::move(text);
          finish(index);
        } else {
          fail(e);
        }
      }
      dispatcher.join();
    } else {
      dispatch();  // an MPI without thread support: the leader only hands out
    }
    return first_failure;
  }

  // Asks for `depth` items at once, then for one more with each result: the next item is there
  // when this one is done. The leader answers in order, and "no more" (-1) once means no more
  // after it: done when `depth` requests have been answered so.
  Outcome follow(const std::function<std::string(long)>& work, int depth) {
    std::string message = "R";
    for (int i = 0; i < depth; ++i)
      MPI_Send(message.data(), 1, MPI_CHAR, 0, kTagAsk, MPI_COMM_WORLD);
    for (int ends = 0; ends < depth;) {
      long item = -1;
      MPI_Request r;
      MPI_Irecv(&item, 1, MPI_LONG, 0, kTagItem, MPI_COMM_WORLD, &r);
      sleepy_wait(r);
      if (item < 0) {
        ++ends;
        continue;
      }
      auto [e, text] = attempt(work, item);
      // Built with append, not "E" + text: GCC 12 reports a false -Wrestrict on the latter.
      message.assign(1, e.ok() ? 'D' : 'E');
      message.append(e.ok() ? text : e.to_text());
      MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kTagAsk,
               MPI_COMM_WORLD);
    }
    return {};
  }

  int m_rank = 0, m_size = 1;
  bool m_threads = false;
};

bool launched_by_mpi() {
  // Open MPI's mpirun, MPICH/Hydra and Slurm's srun (PMI, PMIx) set these in every rank.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

}  // namespace

std::unique_ptr<RunRanks> mpi_ranks_if_launched() {
  if (!launched_by_mpi()) return nullptr;
  return std::make_unique<MpiRanks>();
}

}  // namespace thaw::pipeline
