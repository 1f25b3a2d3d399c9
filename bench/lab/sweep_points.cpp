#include "bench/lab/sweep_points.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "bench/lab/lab_setup.hpp"
#include "bench/lab/table.hpp"
#include "bench/lab/work_precision_scene.hpp"
#include "common/design_image.hpp"
#include "common/png_file.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/scene/scene_file.hpp"
#include "server/service/offline_render.hpp"

namespace flagsim::lab {
namespace {

namespace fs = std::filesystem;

constexpr char kHeader[] = "# flagsim lab points: ";

std::string Format(const Point& point) {
  std::string line;
  for (const auto& [key, value] : point) line += (line.empty() ? "" : " ") + key + "=" + value;
  return line;
}

Point Parse(const std::string& line) {
  Point point;
  std::istringstream words(line);
  std::string word;
  while (words >> word) {
    const size_t equals = word.find('=');
    if (equals == std::string::npos) throw std::runtime_error("not key=value: " + word);
    point[word.substr(0, equals)] = word.substr(equals + 1);
  }
  return point;
}

std::string Field(const Point& point, const std::string& key) {
  const auto found = point.find(key);
  if (found == point.end()) throw std::runtime_error("the point lacks " + key + ": " + Format(point));
  return found->second;
}

struct PointsFile {
  std::string experiment;
  std::vector<Point> points;
  fs::path directory;  ///< where it lies: records/ and the gathered CSV go beside it
};

PointsFile ReadPointsFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  PointsFile file;
  file.directory = fs::path(path).parent_path();
  std::string line;
  if (!std::getline(in, line) || line.rfind(kHeader, 0) != 0)
    throw std::runtime_error(path + ": not a points file (its first line is not '" + kHeader +
                             "EXPERIMENT')");
  file.experiment = line.substr(sizeof(kHeader) - 1);
  while (std::getline(in, line)) {
    if (!line.empty()) file.points.push_back(Parse(line));
  }
  return file;
}

/// "host; CPU model": where a record's cost figures come from.
std::string NodeName() {
  char host[256] = {};
  gethostname(host, sizeof(host) - 1);
  std::string model = "unknown CPU";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  return std::string(host) + "; " + model;
}

/// The record of point `index`: written to a scratch name, then renamed, so that a reader finds
/// it whole or not at all (a task killed midway leaves no record).
void WriteRecord(const fs::path& directory, int index, const std::vector<std::string>& columns,
                 const std::vector<std::string>& row) {
  fs::create_directories(directory / "records");
  const fs::path path = directory / "records" / (std::to_string(index) + ".csv");
  const fs::path scratch = path.string() + ".part-" + std::to_string(getpid());
  {
    std::ofstream out(scratch);
    for (size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
    out << "\n";
    for (size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << row[i];
    out << "\n# node: " << NodeName() << "\n";
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + scratch.string());
  }
  fs::rename(scratch, path);
}

// ---- render -----------------------------------------------------------------------------------

std::vector<std::string> RenderColumns() { return {"scene", "duration_s", "fps", "frames", "frames_sha256"}; }

/// A render point: the scene rendered as flagd render renders it, its frames into `frames`
/// as PNG, and the SHA-256 of their SHA-256s (the pictures, bit for bit).
std::vector<std::string> RenderPointRow(const Point& point, const fs::path& frames) {
  Scene scene = LoadScene(Field(point, "scene"));
  const std::string problem = ParameterTable::Get().Assign("frame_rate", Field(point, "fps"), &scene);
  if (!problem.empty()) throw std::runtime_error(problem);
  fs::create_directories(frames);
  std::string digests;
  const Channels channels;
  OfflineRender render(scene, std::stod(Field(point, "duration")), channels, nullptr,
                       [&](int64_t id, const render::Framebuffer& image) {
                         const std::string png = PngFramePath(frames.string(), id);
                         const std::string failed =
                             WritePng(png, image.width, image.height, image.rgb.data());
                         if (!failed.empty()) throw std::runtime_error(failed);
                         digests += Sha256Hex(image.rgb.data(), image.rgb.size());
                       });
  while (render.Advance()) {
  }
  return {Field(point, "scene"), Field(point, "duration"), Field(point, "fps"),
          std::to_string(render.stats().frames),
          Sha256Hex(reinterpret_cast<const uint8_t*>(digests.data()), digests.size())};
}

std::vector<std::string> ColumnsOf(const std::string& experiment) {
  if (experiment == "work-precision") return WorkPrecisionColumns();
  if (experiment == "render") return RenderColumns();
  throw std::runtime_error("experiment " + experiment + ": allowed work-precision, render");
}

}  // namespace

// ---- work-precision ---------------------------------------------------------------------------

std::vector<Point> WorkPrecisionPoints(const WorkPrecisionScene& scene, bool quick) {
  std::vector<Point> points;
  for (const sim::IntegratorKind kind : AllIntegrators()) {
    const std::string name = sim::IntegratorName(kind);
    if (quick && name != "symplectic_euler" && name != "rk4") continue;
    const std::vector<int> iteration_counts = TakesIterations(kind)
                                                  ? std::vector<int>{2, 10, 50}
                                                  : std::vector<int>{scene.trial.params.solver_iterations};
    for (const int iterations : iteration_counts) {
      Trial trial = scene.trial;
      trial.params.integrator = kind;
      trial.params.solver_iterations = iterations;
      for (const double h : StepSweep(trial, quick ? 3 : 7)) {
        points.push_back({{"integrator", name},
                          {"iterations", TakesIterations(kind) ? std::to_string(iterations) : "-"},
                          {"substeps", std::to_string(SubstepsFor(trial, h))},
                          {"reference_substeps", std::to_string(scene.reference_substeps)}});
      }
    }
  }
  return points;
}

std::vector<std::string> WorkPrecisionPointRow(const Point& point, std::optional<WorkPrecisionScene>* scene) {
  const int reference = std::stoi(Field(point, "reference_substeps"));
  if (!*scene || (*scene)->reference_substeps != reference) scene->emplace(LoadWorkPrecisionScene(reference));
  Trial trial = (*scene)->trial;
  const std::string name = Field(point, "integrator"), iterations = Field(point, "iterations");
  const auto& names = sim::IntegratorNames();
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) throw std::runtime_error("no integrator " + name);
  trial.params.integrator = sim::IntegratorKind(found - names.begin());
  if (iterations != "-") trial.params.solver_iterations = std::stoi(iterations);
  const int substeps = std::stoi(Field(point, "substeps"));
  return WorkPrecisionRow(**scene, name, iterations, trial.horizon / substeps,
                          RunFixed<double>(trial, substeps), CostPerSimulatedSecond(trial, substeps, 3));
}

int WritePoints(const std::string& experiment, const PointsOptions& options, const std::string& directory) {
  std::vector<Point> points;
  if (experiment == "work-precision") {
    points = WorkPrecisionPoints(LoadWorkPrecisionScene(), options.quick);  // converges the reference, once
  } else if (experiment == "render") {
    for (const std::string& scene : options.scenes) {
      LoadScene(scene);  // a scene that does not load is refused now, not in every task
      points.push_back({{"scene", scene},
                        {"duration", Table::Number(options.duration)},
                        {"fps", Table::Number(options.fps)}});
    }
  } else {
    ColumnsOf(experiment);  // throws, naming what is allowed
  }
  fs::create_directories(directory);
  std::ofstream out(fs::path(directory) / "points.txt");
  out << kHeader << experiment << "\n";
  for (const Point& point : points) out << Format(point) << "\n";
  if (!out) throw std::runtime_error("cannot write " + (fs::path(directory) / "points.txt").string());
  return int(points.size());
}

int RunPoints(const std::string& points_file, int index, int chunk) {
  const PointsFile file = ReadPointsFile(points_file);
  const std::vector<std::string> columns = ColumnsOf(file.experiment);
  std::optional<WorkPrecisionScene> scene;
  int status = 0;
  for (int i = index * chunk; i < std::min<int>((index + 1) * chunk, int(file.points.size())); ++i) {
    try {
      const Point& point = file.points[size_t(i)];
      const std::vector<std::string> row =
          file.experiment == "work-precision"
              ? WorkPrecisionPointRow(point, &scene)
              : RenderPointRow(point, file.directory / "renders" / std::to_string(i));
      WriteRecord(file.directory, i, columns, row);
    } catch (const std::exception& error) {
      std::fprintf(stderr, "lab point %d: %s\n", i, error.what());
      status = 1;
    }
  }
  return status;
}

int GatherRecords(const std::string& points_file, int chunk) {
  const PointsFile file = ReadPointsFile(points_file);
  Table table(ColumnsOf(file.experiment), (file.directory / (file.experiment + ".csv")).string());
  std::vector<int> missing;
  std::set<std::string> nodes;
  for (int i = 0; i < int(file.points.size()); ++i) {
    std::ifstream record(file.directory / "records" / (std::to_string(i) + ".csv"));
    std::string header, row, node;
    if (!std::getline(record, header) || !std::getline(record, row)) {
      missing.push_back(i);
      continue;
    }
    if (std::getline(record, node) && node.rfind("# node: ", 0) == 0) nodes.insert(node.substr(8));
    std::vector<std::string> fields;
    std::istringstream cells(row);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    table.Add(fields);
  }
  std::printf("# %zu of %zu points gathered into %s\n", file.points.size() - missing.size(),
              file.points.size(), (file.directory / (file.experiment + ".csv")).c_str());
  for (const std::string& node : nodes) std::printf("# ran on: %s\n", node.c_str());
  std::set<std::string> models;
  for (const std::string& node : nodes) models.insert(node.substr(node.find("; ") + 2));
  if (models.size() > 1)
    std::printf("# costs come from %zu kinds of CPU: compare a cost only with those of its own node\n",
                models.size());
  if (missing.empty()) return 0;
  std::string points, tasks;
  std::set<int> task_set;
  for (const int i : missing) {
    points += (points.empty() ? "" : ",") + std::to_string(i);
    task_set.insert(i / chunk);
  }
  for (const int task : task_set) tasks += (tasks.empty() ? "" : ",") + std::to_string(task);
  std::printf("# missing: points %s (tasks %s)\n", points.c_str(), tasks.c_str());
  return 1;
}

}  // namespace flagsim::lab
