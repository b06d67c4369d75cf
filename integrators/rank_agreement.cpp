#include "integrators/rank_agreement.h"

#include <algorithm>
#include <cstring>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/checkpoint.h"

namespace kasha {
namespace {

// Copies `text` into a fixed field, cut short with "..." if it does not fit.
template <size_t N>
void copyText(char (&out)[N], const std::string& text) {
  if (text.size() < N) {
    std::memcpy(out, text.c_str(), text.size() + 1);
    return;
  }
  std::memcpy(out, text.data(), N - 4);
  std::memcpy(out + N - 4, "...", 4);
}

void addFields(RecordDigest& d, const nlohmann::json& object, const std::string& prefix) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    const std::string name = prefix + it.key();
    if (it.value().is_object()) {
      addFields(d, it.value(), name + ".");
      continue;
    }
    if (d.count == RecordDigest::kFields || name.size() >= sizeof(RecordDigest::Field::name))
      throw std::logic_error("digestRecord: the record has too many fields or too long a name ('" + name + "')");
    RecordDigest::Field& f = d.fields[d.count++];
    copyText(f.name, name);
    const std::string text = it.value().dump();
    copyText(f.value, text);
    f.hash = hashBytes(text.data(), text.size());
  }
}

}  // namespace

RecordDigest digestRecord(const nlohmann::json& record) {
  if (!record.is_object()) throw std::logic_error("digestRecord: the record is not an object");
  RecordDigest d;
  addFields(d, record, "");
  std::sort(d.fields.begin(), d.fields.begin() + d.count,
            [](const RecordDigest::Field& a, const RecordDigest::Field& b) { return reportedBefore(a.name, b.name); });
  return d;
}

std::string firstDifference(const RecordDigest& root, const RecordDigest& other, int rank) {
  // Both are in reportedBefore's order: walk them together. A name that only one side has is a
  // difference too.
  uint32_t i = 0, j = 0;
  const auto describe = [&](const char* name, const char* rootValue, const char* otherValue) {
    return std::string(name) + " (rank 0: " + rootValue + ", rank " + std::to_string(rank) + ": " + otherValue + ")";
  };
  for (; i < root.count || j < other.count;) {
    const int order = i == root.count                                          ? 1
                      : j == other.count                                       ? -1
                      : reportedBefore(root.fields[i].name, other.fields[j].name) ? -1
                      : reportedBefore(other.fields[j].name, root.fields[i].name) ? 1
                                                                                   : 0;
    if (order < 0) return describe(root.fields[i].name, root.fields[i].value, "none");
    if (order > 0) return describe(other.fields[j].name, "none", other.fields[j].value);
    if (root.fields[i].hash != other.fields[j].hash)
      return describe(root.fields[i].name, root.fields[i].value, other.fields[j].value);
    ++i, ++j;
  }
  return {};
}

void requireSameRecord(RenderGroup& group, const nlohmann::json& record) {
  const RecordDigest mine = digestRecord(record);
  std::vector<RecordDigest> all(group.rank() == 0 ? size_t(group.size()) : 0);
  group.gatherToRoot(std::as_bytes(std::span(&mine, 1)), std::as_writable_bytes(std::span(all)));
  std::string difference;
  int disagreeing = 0;  // the lowest rank that differs; 0: none
  for (int r = 1; r < int(all.size()) && disagreeing == 0; ++r)
    if (difference = firstDifference(mine, all[size_t(r)], r); !difference.empty()) disagreeing = r;
  int verdict[1] = {disagreeing};
  group.maxOverRanks(verdict);  // only rank 0's is not 0
  if (verdict[0] == 0) return;
  if (group.rank() == 0) throw RanksDisagree("rank " + std::to_string(verdict[0]) + " disagrees with rank 0 on " + difference, true);
  throw RanksDisagree("rank " + std::to_string(verdict[0]) + " disagrees with rank 0 (rank 0 says on what)", false);
}

}  // namespace kasha
