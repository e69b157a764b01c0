#include <qverify/report/candidate_section.hpp>

namespace qverify {

using json = nlohmann::ordered_json;

json candidate_head_json(const Candidate& c, double accuracy) {
  return {{"name", c.name},
          {"source", "candidate"},
          {"command", c.description},
          {"timeout_seconds", c.timeout_seconds > 0 ? json(c.timeout_seconds) : json(nullptr)},
          {"accuracy", accuracy}};
}

json reproducer_json(const Reproducer& r) {
  json e{{"family", r.family}, {"k", r.k}, {"param", r.param}, {"reason", r.reason}, {"scene", r.scene}};
  e["returned"] = r.returned ? json(*r.returned) : json(nullptr);
  e["log"] = r.log;
  return e;
}

}  // namespace qverify
