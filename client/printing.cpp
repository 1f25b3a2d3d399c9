#include "client/printing.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <vector>

#include "common/printable_text.hpp"

namespace flagsim {
namespace {

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

std::string Range(const parameter_t& row) {
  switch (row.kind) {
    case parameter_t::BOOLEAN:
      return "true|false";
    case parameter_t::CHOICE: {
      std::string names;
      for (const std::string& choice : row.choices) names += (names.empty() ? "" : "|") + choice;
      return names;
    }
    default:
      return Number(row.min_value) + " .. " + Number(row.max_value);
  }
}

std::string DefaultText(const parameter_t& row) {
  if (row.kind == parameter_t::BOOLEAN) return row.default_value != 0 ? "true" : "false";
  if (row.kind == parameter_t::CHOICE) {  // an index, unless the message is damaged
    const bool index = row.default_value >= 0 && row.default_value < double(row.choices.size());
    return index ? row.choices[size_t(row.default_value)] : Number(row.default_value);
  }
  return Number(row.default_value);
}

}  // namespace

void PrintParams(const params_t& params, std::ostream& out) {
  // Each string from the bus through TerminalText: what a server sends cannot drive the terminal.
  std::vector<std::array<std::string, 6>> rows = {
      {"name", "value", "unit", "range", "default", "description"}};
  for (const parameter_t& row : params.parameters) {
    rows.push_back({TerminalText(row.name), TerminalText(row.value_text), TerminalText(row.unit),
                    TerminalText(Range(row)), TerminalText(DefaultText(row)), TerminalText(row.description)});
  }
  size_t name_width = 0, value_width = 0, unit_width = 0, range_width = 0;
  for (const auto& row : rows) {
    name_width = std::max(name_width, row[0].size());
    value_width = std::max(value_width, row[1].size());
    unit_width = std::max(unit_width, row[2].size());
    range_width = std::max(range_width, row[3].size());
  }
  char line[1024];
  for (const auto& [name, value, unit, range, fallback, description] : rows) {
    std::snprintf(line, sizeof(line), "%-*s  %-*s  %-*s  %-*s  %-10s  %s\n", int(name_width), name.c_str(),
                  int(value_width), value.c_str(), int(unit_width), unit.c_str(), int(range_width),
                  range.c_str(), fallback.c_str(), description.c_str());
    out << line;
  }
}

namespace {

/// "model:  32 x 24, symplectic_euler, 12 substeps; auto chooses integrator and grid" and auto's
/// estimate and word.
void PrintModel(const status_t& status, std::ostream& out) {
  char text[512];
  std::snprintf(text, sizeof(text), "model:             %d x %d, %s, %d substeps; auto chooses %s\n", status.cols,
                status.rows, TerminalText(status.integrator).c_str(), status.substeps,
                TerminalText(status.model_auto).c_str());
  out << text;
  if (status.screen_error_px >= 0) {
    std::snprintf(text, sizeof(text), "screen_error:      %.2g px estimated, %.2g of real time by the cost model\n",
                  status.screen_error_px, status.model_cost);
    out << text;
  }
  if (!status.model_note.empty()) out << "auto:              " << TerminalText(status.model_note) << "\n";
}

/// "clock:  paused, 12 steps owed; time_scale 0.5".
void PrintClock(const status_t& status, std::ostream& out) {
  char text[160];
  const char* running = status.paused ? (status.steps_owed > 0 ? "paused, stepping" : "paused") : "running";
  std::snprintf(text, sizeof(text), "clock:             %s%s; time_scale %g (simulated s per wall s)\n", running,
                status.steps_owed > 0 ? (", " + std::to_string(status.steps_owed) + " steps owed").c_str() : "",
                status.time_scale);
  out << text;
}

}  // namespace

void PrintStatus(const status_t& status, std::ostream& out) {
  char text[4096];
  std::snprintf(text, sizeof(text),
                "uptime:            %.1f s\n"
                "sim time:          %.3f s (step %lld)\n"
                "real-time factor:  %.3f\n"
                "steps per second:  %.1f (%d substeps each, %.1f us per step)\n"
                "flag:              %d nodes, %s, %d thread(s)%s\n"
                "state rate:        %.1f Hz (%.1f us to publish)\n"
                "frames:            %.1f Hz, %.0f us to draw, %.0f us to encode, %.1f tiles and %.0f bytes "
                "each, %lld skipped\n"
                "bytes per second:  %.0f\n"
                "commands:          %lld accepted, %lld rejected, %lld undecodable dropped\n"
                "recoveries:        %lld\n",
                status.uptime, status.sim_time, static_cast<long long>(status.step), status.real_time_factor,
                status.steps_per_second, status.substeps, status.step_time_us, status.num_nodes,
                TerminalText(status.integrator).c_str(), status.threads, status.sleeping ? ", sleeping" : "",
                status.state_rate_hz, status.publish_time_us, status.frame_rate_hz, status.render_time_us,
                status.encode_time_us, status.tiles_per_frame, status.frame_bytes,
                static_cast<long long>(status.frames_skipped), status.bytes_per_second,
                static_cast<long long>(status.commands_accepted),
                static_cast<long long>(status.commands_rejected),
                static_cast<long long>(status.messages_dropped), static_cast<long long>(status.recoveries));
  out << text;
  PrintClock(status, out);
  PrintModel(status, out);
  if (!status.last_recovery.empty())
    out << "last recovery:     " << TerminalText(status.last_recovery) << "\n";
  out << "authentication:    " << TerminalText(status.command_authentication) << "\n";
  const int64_t refused = status.commands_unsigned + status.commands_unknown_key + status.commands_bad_mac +
                          status.commands_replayed + status.commands_stale;
  if (refused > 0) {
    std::snprintf(
        text, sizeof(text),
        "refused:           %lld unsigned, %lld unknown key, %lld bad MAC, %lld replayed, %lld stale\n",
        static_cast<long long>(status.commands_unsigned), static_cast<long long>(status.commands_unknown_key),
        static_cast<long long>(status.commands_bad_mac), static_cast<long long>(status.commands_replayed),
        static_cast<long long>(status.commands_stale));
    out << text;
  }
  std::snprintf(text, sizeof(text), "server:            id %016llx",
                static_cast<unsigned long long>(status.server_id));
  out << text;
  if (status.other_servers > 0) {
    out << ", and " << status.other_servers
        << " other server(s) on this prefix: each takes every command, their streams interleave";
  }
  out << "\n";
}

namespace {

std::string Triple(const double (&v)[3]) { return Number(v[0]) + " " + Number(v[1]) + " " + Number(v[2]); }

std::string LawName(int8_t law) {
  static const char* const names[] = {"step", "linear", "smooth", "cubic"};  // LAW_* order
  return law >= 0 && law < 4 ? names[law] : Number(law);
}

/// time, law, wind, gust, camera, parameters: one key's columns.
std::vector<std::string> KeyColumns(const timeline_key_t& key) {
  std::string parameters;
  for (size_t i = 0; i < key.names.size() && i < key.values.size(); ++i) {
    parameters += (i ? " " : "") + TerminalText(key.names[i]) + "=" + Number(key.values[i]);
  }
  return {Number(key.time),
          LawName(key.law),
          key.has_wind ? Triple(key.wind_velocity) : "-",
          key.has_wind ? Number(key.wind_gust) : "-",
          key.has_camera ? "eye " + Triple(key.camera_eye) + ", target " + Triple(key.camera_target) +
                               ", fov " + Number(key.camera_fov)
                         : "-",
          parameters.empty() ? "-" : parameters};
}

}  // namespace

void PrintTimeline(const timeline_t& timeline, std::ostream& out) {
  out << (timeline.playing ? "playing" : "paused") << " at " << Number(timeline.position) << " s of "
      << Number(timeline.last_key_time) << " s, speed " << Number(timeline.speed) << ", loop "
      << (timeline.loop ? "on" : "off") << (timeline.gliding ? ", gliding" : "") << ", " << timeline.num_keys
      << " key(s)\n";
  if (timeline.keys.empty()) return;
  std::vector<std::vector<std::string>> rows = {
      {"time", "law", "wind m/s", "gust", "camera m, deg", "parameters"}};
  for (const timeline_key_t& key : timeline.keys) rows.push_back(KeyColumns(key));
  std::vector<size_t> widths(rows[0].size(), 0);
  for (const auto& row : rows) {
    for (size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  }
  for (const auto& row : rows) {
    std::string line;
    for (size_t c = 0; c < row.size(); ++c) {
      line += row[c] + (c + 1 < row.size() ? std::string(widths[c] - row[c].size() + 2, ' ') : "");
    }
    out << line << "\n";
  }
}

std::string TipText(const state_t& state) {
  const size_t tip = 3 * static_cast<size_t>(std::max<int64_t>(int64_t(state.cols) - 1, 0));
  if (state.cols <= 0 || tip + 2 >= state.position.size()) return "(none)";
  char text[96];
  std::snprintf(text, sizeof(text), "(%.3f, %.3f, %.3f)", state.position[tip], state.position[tip + 1],
                state.position[tip + 2]);
  return text;
}

}  // namespace flagsim
