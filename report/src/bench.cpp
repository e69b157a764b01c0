#include <qverify/report/bench.hpp>

#include <fmt/format.h>

#include <iterator>

namespace qverify {

using json = nlohmann::ordered_json;

namespace {

/// A row, fields in the document's order (the verification rows' order is their own).
json row_json(const BenchRow& row) {
  json r;
  if (row.verify) {
    const VerifyRowFacts& v = *row.verify;
    const double pps = row.items_per_s;
    r = {{"op", row.op},
         {"precision", row.precision},
         {"inputs", row.inputs},
         {"points_per_s", pps},
         {"threads", v.threads},
         {"exact_fallbacks", v.counts.fallbacks},
         {"points", v.counts.checked},
         {"exact_fallbacks_measured", v.counts.measured},
         {"points_per_s_per_thread", pps / v.threads},
         {"method", row.method},
         {"n", row.n},
         {"distinct_points", v.distinct_points},
         {"passes", v.passes},
         {"checks_failed", v.counts.failed}};
  } else {
    r = {{"op", row.op}, {"precision", row.precision}, {"method", row.method}, {"inputs", row.inputs}, {"n", row.n}};
  }
  r["items_per_s"] = row.items_per_s;
  r["ns_per_item"] = row.ns_per_item;
  r["ns_per_item_median"] = row.ns_per_item_median;
  r["ns_per_item_runs"] = row.ns_per_item_runs;
  r["bytes_per_item"] = row.bytes_per_item;
  r["roofline_fraction"] = row.roofline_fraction;
  if (!row.arithmetic.empty()) r["arithmetic"] = row.arithmetic;
  if (!row.results.empty()) r["results"] = row.results;
  if (row.items_beyond_bit_bound) r["items_beyond_bit_bound"] = *row.items_beyond_bit_bound;
  if (row.items_singly) r["items_singly"] = *row.items_singly;
  if (row.cost_vs_double_direct) r["cost_vs_double_direct"] = *row.cost_vs_double_direct;
  return r;
}

/// The "inputs" section: how each kind of input is drawn and converted (as studies/src/bench.cpp draws them).
json inputs_json(const BenchReport& b) {
  return {{"small-rational", "random rationals p/q, |p| <= 20, 1 <= q <= 9 (doubles: rounded once; intervals: the "
                             "enclosure of p/q; exact: as p and q): quadrics A, and lights (x, y, z, 1) with z != 0 "
                             "that are also the mirror planes x X + y Y + z Z + 1 = 0"},
          {"double-valued", "random doubles with full 53-bit mantissas, |x| in [2^e, 2^(e+1)) with e uniform in "
                            "-30..30 for every entry independently, random signs (A's ten entries; the light's x, y, "
                            "z, w = 1); intervals: the points; exact: the doubles' values"},
          {"decimal-17", "decimal text with 17 significant digits, |x| in [10^k, 10^(k+1)) with k uniform in -9..8 "
                         "(about 2^-30..2^30), random signs; doubles: the nearest double (std::from_chars); "
                         "intervals: that double +- one ulp (an enclosure of the text's value); exact: the text's "
                         "value m 10^e"},
          {"generation_s", b.generation_s}};
}

/// The "timing": the order of the phases and what each row's numbers are.
std::string timing_note(const BenchReport& b) {
  const std::string R = std::to_string(b.rounds);
  return "best of " + R + " rounds; each round runs the copy, then for each kind of input (converted into "
         "the same buffers, untimed) the four double and interval direct rows once, and the copy again (so that "
         "rows and bandwidth sample the same moments of a shared machine, whose noise only adds time); then the "
         "paper rows of each kind, best of " + R + " rounds; then the exact rows of each kind, best of " + R +
         " runs (small-rational: all n items; double-valued and decimal-17: the first " + std::to_string(b.exact_items) +
         " items, the row's n); then the verification rows, best of " + R + " rounds. Outputs pre-allocated; "
         "ns_per_item_runs lists every run, ns_per_item_median is the median";
}

/// The "exact_arithmetic" section: the candidates for exact results from doubles (one thread each).
json exact_arithmetic_json(const BenchReport& b) {
  json candidates = json::array();
  for (const ExactArithmeticCandidate& c : b.exact_arithmetic)
    candidates.push_back({{"arithmetic", c.arithmetic},
                          {"note", c.note},
                          {"shadow_ns_per_item", c.shadow_ns_per_item},
                          {"reflection_ns_per_item", c.reflection_ns_per_item}});
  return {{"inputs", "double-valued"},
          {"items", b.exact_arithmetic_items},
          {"threads", 1},
          {"note", "the candidates for exact results from doubles, timed on the same items by the same generic "
                   "formulas (the direct shadow; the division-free mirror matrix and rank-one image), all of them in each of " +
                       std::to_string(b.rounds) + " rounds, best of the rounds, one thread"},
          {"candidates", candidates}};
}

/// The "verification" section: the items, the sampling and what the rows check.
json verification_json(const BenchVerification& v) {
  return {
      {"inputs", "double-valued"},
      {"items_drawn", v.items_drawn},
      {"shadow_items", v.shadow_items},
      {"reflection_items", v.reflection_items},
      {"samples_per_item", v.samples_per_item},
      {"accuracy", v.accuracy},
      {"sampling_s", {{"shadow", v.sampling_shadow_s}, {"reflection", v.sampling_reflection_s}}},
      {"sampling_note",
       "sampling the exact points (terminator points A ∩ {(A L).x = 0}, points of A reflected exactly, in Q(sqrt d), "
       "accuracy.hpp) and preparing them (enclosures, denominators cleared) is not part of the timed checks; "
       "sampling_s is its wall time on the same threads"},
      {"candidates",
       "precision double: the exact results correctly rounded to double (P, polar plane, R; B), checked by the "
       "filter (point_filter.hpp: certified interval evaluation of the verifier's distance rule against T * object "
       "size; the pairs it cannot decide, exact_fallbacks, are decided on exact integers with MPFR enclosures and, "
       "within about 1e-15 of the boundary, by the verifier's 80-digit measure: exact_fallbacks_measured); "
       "precision exact: the exact results "
       "(rationals), proof mode (x^T Q x == 0 exactly, on GMP integers)"},
      {"points_note",
       "points counts the (point, result) pairs checked per run, the sets `verify` measures (accuracy.hpp): P, the "
       "polar plane and R at each terminator point, P at points of the cone's generator lines, R at rational points of "
       "the polar plane (verify-shadow); B at each reflected point (verify-reflection); passes: the filtered rows check "
       "every pair that many times per run (about 4 10^6 checks), the exact rows once"}};
}

json optional_text(const std::optional<std::string>& s) { return s ? json(*s) : json(nullptr); }
json optional_number(const std::optional<int>& v) { return v ? json(*v) : json(nullptr); }

/// The "processor": what processor_info found and where it looked.
json processor_json(const ProcessorInfo& p) {
  return {{"vendor", optional_text(p.vendor)},
          {"model_name", optional_text(p.model_name)},
          {"family", optional_number(p.family)},
          {"model", optional_number(p.model)},
          {"instruction_set", p.instruction_set},
          {"lanes", p.lanes},
          {"double_kernel", p.double_kernel},
          {"interval_kernel", p.interval_kernel},
          {"exact_kernel", p.exact_kernel},
          {"exact_lanes", p.exact_lanes},
          {"supports", p.supports},
          {"logical_cpus", p.logical_cpus},
          {"source", "/proc/cpuinfo (first processor); instruction_set: what this build was compiled for; double_kernel, "
                     "lanes: what the double batches run here (a second kernel compiled for another instruction set or by "
                     "another compiler, chosen at run time, where the build measured it faster), and its doubles per "
                     "instruction; "
                     "interval_kernel: the same for the interval batches; exact_kernel, exact_lanes: the same for the exact "
                     "digit blocks (exact/digit_batch.hpp), and the items of a block"}};
}

json pages_json(const BenchPages& p) {
  return {{"huge_pages_advised", p.huge_pages_advised},
          {"advised_bytes", p.advised_bytes},
          {"transparent_huge_pages", p.transparent_huge_pages},
          {"buffer_bytes", p.buffer_bytes},
          {"buffer_huge_page_bytes", p.buffer_huge_page_bytes},
          {"note", "the buffers of the double and interval rows and of the bandwidth copy, all advised huge pages or "
                   "none (--no-huge-pages; batch/pages.hpp): huge_pages_advised when asked and the system took the "
                   "advice (advised_bytes, the whole huge pages inside the buffers); transparent_huge_pages: the "
                   "system's mode (/sys/kernel/mm/transparent_hugepage/enabled); buffer_huge_page_bytes: the huge "
                   "pages of the mappings holding those buffers once they were written (/proc/self/smaps; a mapping that also "
                   "holds other data counts at most its bytes of the buffers: an upper bound there)"}};
}

}  // namespace

json bench_json(const BenchReport& b) {
  json rows = json::array();
  for (const BenchRow& r : b.rows) rows.push_back(row_json(r));
  return {{"format", "qverify-bench/1"},
          {"threads", b.threads},
          {"n", b.n},
          {"processor", processor_json(b.processor)},
          {"memory_bandwidth_gbps", b.memory_bandwidth_gbps},
          {"memory_bandwidth_gbps_runs", b.memory_bandwidth_gbps_runs},
          {"bandwidth_method", "parallel stream copy (non-temporal stores, like the double batches) of as many bytes "
                               "as the double shadow row moves (read + write), on the same kind of pages as the rows (pages), run at the "
                               "start and at the end of each of the " +
                                   std::to_string(b.rounds) + " rounds, around the rows; the best copy"},
          {"pages", pages_json(b.pages)},
          {"inputs", inputs_json(b)},
          {"timing", timing_note(b)},
          {"simd", {{"lanes", b.processor.lanes},
                    {"instruction_set", b.processor.double_kernel},
                    {"interval_instruction_set", b.processor.interval_kernel},
                    {"note", "double and interval batches run W items per instruction (batch/pack.hpp): the "
                             "double batches on instruction_set (exact/double_batch.hpp), W = lanes; the "
                             "interval batches on interval_instruction_set (exact/interval_batch.hpp)"}}},
          {"exact_arithmetic", exact_arithmetic_json(b)},
          {"verification", verification_json(b.verification)},
          {"rows", rows}};
}

std::string bench_text(const BenchReport& b) {
  std::string out;
  auto put = std::back_inserter(out);
  const ProcessorInfo& cpu = b.processor;
  auto number = [](const std::optional<int>& v) { return v ? std::to_string(*v) : std::string("null"); };
  fmt::format_to(put,
                 "{} items, {} threads, memory bandwidth {:.2f} GB/s (measured in this run); build: {}; double batches: "
                 "{}, {} lanes; interval batches: {}; exact digit blocks: {}, {} items at once\n"
                 "processor: {} {} (family {}, model {})\npages: {} MiB of buffers, {}; {} MiB of them on huge "
                 "pages (transparent huge pages: {})\n\n",
                 b.n, b.threads, b.memory_bandwidth_gbps, cpu.instruction_set, cpu.double_kernel, cpu.lanes,
                 cpu.interval_kernel,
                 cpu.exact_kernel, cpu.exact_lanes,
                 cpu.vendor.value_or("?"),
                 cpu.model_name.value_or("?"), number(cpu.family), number(cpu.model), b.pages.buffer_bytes >> 20,
                 b.pages.huge_pages_advised ? fmt::format("{} MiB advised huge pages", b.pages.advised_bytes >> 20)
                                            : std::string("not advised"),
                 b.pages.buffer_huge_page_bytes >> 20,
                 b.pages.transparent_huge_pages.empty() ? std::string("unknown") : b.pages.transparent_huge_pages);
  fmt::format_to(put, "{:<17} {:<9} {:<8} {:<14} {:>12} {:>10} {:>6} {:>8} {:>9}\n", "op", "precision", "method", "inputs",
                 "items/s", "ns/item", "bytes", "roofline", "x double");
  for (const BenchRow& r : b.rows) {
    fmt::format_to(put, "{:<17} {:<9} {:<8} {:<14} {:>12.4g} {:>10.2f} {:>6} {:>8.2f} ", r.op, r.precision, r.method,
                   r.inputs, r.items_per_s, r.ns_per_item, r.bytes_per_item, r.roofline_fraction);
    // every row has a double row of its op and inputs to compare with, unless that row had no point to check
    if (r.cost_vs_double_direct) fmt::format_to(put, "{:>9.1f}", *r.cost_vs_double_direct);
    else fmt::format_to(put, "{:>9}", "-");
    if (r.verify)  // verification rows: point checks
      fmt::format_to(put, "  {:.3g} checks/s per thread{}", r.items_per_s / r.verify->threads,
                     r.precision == "exact" ? std::string(", proof mode")
                                            : fmt::format(", {} of {} past the filter", r.verify->counts.fallbacks,
                                                          r.verify->counts.checked));
    out += "\n";
  }
  fmt::format_to(put,
                 "\nverification rows: point checks ((point, result) pairs) of double-valued items; sampling the exact "
                 "points took {:.2f} s (shadow) and {:.2f} s (reflection), not timed in the rows\n",
                 b.verification.sampling_shadow_s, b.verification.sampling_reflection_s);
  return out;
}

}  // namespace qverify
