#include "app/time_series.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <regex>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace neomesh::app {

namespace {

double parse_number(const std::string& spec, const std::string& field) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
  if (field.empty() || ec != std::errc() || end != field.data() + field.size() || !std::isfinite(v))
    fail("--time '{}': expected START:END:STEPS, e.g. 0:1:20", spec);
  return v;
}

}  // namespace

std::vector<double> parse_time_steps(const std::string& spec) {
  const auto first = spec.find(':'), second = spec.find(':', first + 1);
  if (first == std::string::npos || second == std::string::npos ||
      spec.find(':', second + 1) != std::string::npos)
    fail("--time '{}': expected START:END:STEPS, e.g. 0:1:20", spec);
  const double start = parse_number(spec, spec.substr(0, first));
  const double end = parse_number(spec, spec.substr(first + 1, second - first - 1));
  const std::string count_text = spec.substr(second + 1);
  int count = 0;
  const auto [stop, ec] =
      std::from_chars(count_text.data(), count_text.data() + count_text.size(), count);
  if (count_text.empty() || ec != std::errc() || stop != count_text.data() + count_text.size())
    fail("--time '{}': the number of steps must be a whole number", spec);
  if (count < 1 || count > 100000)
    fail("--time '{}': the number of steps must be between 1 and 100000 (got {})", spec, count);
  std::vector<double> times(count);
  for (int i = 0; i < count; ++i)
    times[i] = count == 1 ? start : start + (end - start) * i / (count - 1);
  return times;
}

std::filesystem::path series_member(const std::filesystem::path& output, int step) {
  const std::string extension = output.extension() == ".pvd" ? ".vtu" : output.extension().string();
  std::filesystem::path member = output;
  member.replace_filename(fmt::format("{}-{:04d}{}", output.stem().string(), step, extension));
  return member;
}

std::string numbered_path(const std::string& option, const std::string& pattern, int step) {
  static const std::regex conversion("%(0?[0-9]?)d");
  std::smatch m;
  const auto percents = std::count(pattern.begin(), pattern.end(), '%');
  if (pattern.size() > 4096 || percents != 1 || !std::regex_search(pattern, m, conversion))
    fail("{} {}: with --time, give a pattern with one %d for the step, e.g. frames/%04d.png",
         option, pattern);
  const std::string flags = m[1];
  const int width = flags.empty() ? 0 : flags.back() - '0';  // one digit: %04d
  const std::string number = flags.starts_with('0') ? fmt::format("{:0{}d}", step, width)
                                                    : fmt::format("{:{}d}", step, width);
  return m.prefix().str() + number + m.suffix().str();
}

void write_pvd(const std::filesystem::path& path, const std::vector<double>& times,
               const std::vector<std::filesystem::path>& members) {
  AtomicFile file(path);
  std::ofstream& out = file.stream();
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <Collection>\n";
  for (std::size_t i = 0; i < members.size(); ++i)
    out << fmt::format("    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
                       times[i], members[i].filename().string());
  out << "  </Collection>\n</VTKFile>\n";
  file.commit();
}

}  // namespace neomesh::app
