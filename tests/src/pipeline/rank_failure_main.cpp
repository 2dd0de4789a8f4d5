// A test program run under `mpirun -np 2` (test_rank_failure_mpi.cpp): every rank runs a step that
// fails on one rank only, through thaw run's own paths between ranks (on_every_rank, on_leader,
// the farm in coarse and fine grain, end_on_ranks) and thaw's own command boundary (run_app), so
// the exit code and the one error line are those thaw run would give.
//   rank_failure fail --kind user|internal --path every|leader|coarse|fine [--on-rank N]
#include <CLI/CLI.hpp>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>

#include "base/error.h"
#include "base/outcome.h"
#include "src/cli/app.h"
#include "src/pipeline/rank_agreement.h"
#include "src/pipeline/run_ranks.h"

namespace {

using namespace thaw;

void fail_here(const std::string& kind) {
  if (kind == "user") throw UserError("rank1.toml", "[film] fps", "must be > 0 (got -1)");
  throw std::logic_error("an invariant broke on this rank");
}

void run_step(const std::string& kind, const std::string& path, int on_rank) {
  std::unique_ptr<pipeline::RunRanks> ranks = pipeline::mpi_ranks_if_launched();
  if (!ranks) ranks = pipeline::single_process();
  const bool here = ranks->rank() == on_rank;
  const Outcome mine = Outcome::of([&] {
    if (path == "every") {
      pipeline::on_every_rank(*ranks, [&] {
        if (here) fail_here(kind);
      });
    } else if (path == "leader") {
      pipeline::on_leader(*ranks, [&] {
        if (here) fail_here(kind);
      });
    } else {
      // The failing rank fails at once; the others' items last long enough that it gets one.
      const auto grain = path == "coarse" ? WorkFarm::Grain::coarse : WorkFarm::Grain::fine;
      ranks->run(
          64, 1,
          [&](long) {
            if (here) fail_here(kind);
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            return std::string();
          },
          {}, grain);
    }
  });
  pipeline::end_on_ranks(ranks, mine);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("rank failure test");
  thaw::cli::describe_app(app);
  std::string kind = "user", path = "every";
  int on_rank = 1;
  CLI::App* fail = app.add_subcommand("fail", "fail on one rank");
  fail->add_option("--kind", kind)->check(CLI::IsMember({"user", "internal"}));
  fail->add_option("--path", path)->check(CLI::IsMember({"every", "leader", "coarse", "fine"}));
  fail->add_option("--on-rank", on_rank);
  fail->callback([&] { run_step(kind, path, on_rank); });
  app.require_subcommand(1);
  return thaw::cli::run_app(app, argc, argv);
}
