// Ranks that disagree (integrators/rank_agreement.h): rank 0 compares the fixed-size digests of
// every rank's record and names the first field that differs, in the order that names the cause
// (the integrator before the settings it implies, scene_hash after the settings it also covers).
// The ranks are threads (tests/thread_group.h); the MPI form runs the kasha binary under mpirun
// (tests/mpi/mpi_render_test.sh, mode disagree).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "integrators/rank_agreement.h"
#include "tests/thread_group.h"

namespace kasha {
namespace {

using nlohmann::json;

const json kRecord = {{"integrator", "ppm"},
                      {"seed", 1},
                      {"scene_hash", "0123456789abcdef"},
                      {"hero_wavelengths", 4},
                      {"ppm", {{"direct", "nee-elastic"}, {"alpha", 0.7}}}};

// The difference of `other` from kRecord, as rank `rank` would be told.
std::string differenceFrom(const json& other, int rank = 1) {
  return firstDifference(digestRecord(kRecord), digestRecord(other), rank);
}

TEST(RankAgreement, TheSameRecordAgrees) {
  EXPECT_EQ(differenceFrom(kRecord), "");
  json reordered = json::object();  // the order of insertion does not matter
  for (const char* key : {"ppm", "hero_wavelengths", "scene_hash", "seed", "integrator"}) reordered[key] = kRecord[key];
  EXPECT_EQ(differenceFrom(reordered), "");
}

TEST(RankAgreement, NamesTheFieldAndBothValues) {
  json other = kRecord;
  other["seed"] = 2;
  EXPECT_EQ(differenceFrom(other, 3), "seed (rank 0: 1, rank 3: 2)");
  other = kRecord;
  other["ppm"]["direct"] = "photons";
  EXPECT_EQ(differenceFrom(other), "ppm.direct (rank 0: \"nee-elastic\", rank 1: \"photons\")");
  other = kRecord;
  other["bdpt"] = {{"mollify_alpha", 0.5}};
  EXPECT_EQ(differenceFrom(other), "bdpt.mollify_alpha (rank 0: none, rank 1: 0.5)");
  other = kRecord;
  other.erase("seed");
  EXPECT_EQ(differenceFrom(other), "seed (rank 0: 1, rank 1: none)");
}

TEST(RankAgreement, TheIntegratorFirstTheSceneHashLast) {
  json other = kRecord;
  other["integrator"] = "pt";
  other["hero_wavelengths"] = 1;
  other.erase("ppm");
  EXPECT_EQ(differenceFrom(other).rfind("integrator (rank 0: \"ppm\", rank 1: \"pt\")", 0), 0u) << differenceFrom(other);
  other = kRecord;
  other["scene_hash"] = "fedcba9876543210";  // --set ppm.alpha=0.5 changes both
  other["ppm"]["alpha"] = 0.5;
  EXPECT_EQ(differenceFrom(other).rfind("ppm.alpha", 0), 0u) << differenceFrom(other);
  other["ppm"]["alpha"] = 0.7;
  EXPECT_EQ(differenceFrom(other).rfind("scene_hash", 0), 0u) << differenceFrom(other);
}

TEST(RankAgreement, LongValuesAreComparedWhole) {
  json a = kRecord, b = kRecord;
  a["spectral_bins"] = std::string(200, 'x') + "a";
  b["spectral_bins"] = std::string(200, 'x') + "b";
  const std::string d = firstDifference(digestRecord(a), digestRecord(b), 1);
  EXPECT_EQ(d.rfind("spectral_bins (rank 0: \"xxx", 0), 0u) << d;
  EXPECT_NE(d.find("...,"), std::string::npos) << d;  // the text is cut short, the hash is of all of it
}

TEST(RankAgreement, ARecordTooLargeForTheDigestIsAProgrammingError) {
  json many = json::object();
  for (int i = 0; i <= RecordDigest::kFields; ++i) many[std::to_string(i)] = i;
  EXPECT_THROW(digestRecord(many), std::logic_error);
  EXPECT_THROW(digestRecord({{std::string(40, 'k'), 1}}), std::logic_error);
}

// Through a group: every rank learns that they disagree; rank 0's error is the one to print.
TEST(RankAgreement, EveryRankStopsAndRankZeroSaysWhy) {
  for (const int differing : {0, 1, 2}) {  // the rank given another seed; 0: none
    SCOPED_TRACE(differing);
    test::ThreadGroup group(3);
    std::vector<std::string> errors(3);
    std::vector<int> printed(3, -1);  // -1: no error
    std::vector<std::thread> ranks;
    for (int r = 0; r < 3; ++r)
      ranks.emplace_back([&, r] {
        test::ThreadGroup::Rank rank(group, r);
        json record = kRecord;
        if (r == differing && r > 0) record["seed"] = 5;
        try {
          requireSameRecord(rank, record);
        } catch (const RanksDisagree& e) {
          errors[size_t(r)] = e.what();
          printed[size_t(r)] = e.print();
        }
      });
    for (std::thread& t : ranks) t.join();
    if (differing == 0) {
      EXPECT_EQ(printed, std::vector<int>({-1, -1, -1}));
      continue;
    }
    EXPECT_EQ(printed, std::vector<int>({1, 0, 0}));
    EXPECT_EQ(errors[0], "--mpi: rank " + std::to_string(differing) + " disagrees with rank 0 on seed (rank 0: 1, rank " +
                             std::to_string(differing) + ": 5)");
  }
}

}  // namespace
}  // namespace kasha
