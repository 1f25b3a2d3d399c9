// A result table: printed aligned on stdout as rows come, and written as CSV at the end when a
// file is given. Every lab experiment reports through one.
#pragma once

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace flagsim::lab {

class Table {
 public:
  Table(std::vector<std::string> columns, std::string csv_path)
      : columns_(std::move(columns)), csv_path_(std::move(csv_path)) {
    for (const std::string& column : columns_) std::printf("%-*s", Width(column), column.c_str());
    std::printf("\n");
  }

  ~Table() {
    if (csv_path_.empty()) return;
    std::ofstream csv(csv_path_);
    for (size_t i = 0; i < columns_.size(); ++i) csv << (i ? "," : "") << columns_[i];
    csv << "\n";
    for (const auto& row : rows_) {
      for (size_t i = 0; i < row.size(); ++i) csv << (i ? "," : "") << row[i];
      csv << "\n";
    }
  }

  /// One row, one text per column (see Number for figures).
  void Add(std::vector<std::string> row) {
    for (size_t i = 0; i < row.size() && i < columns_.size(); ++i) {
      std::printf("%-*s", Width(columns_[i]), row[i].c_str());
    }
    std::printf("\n");
    std::fflush(stdout);
    rows_.push_back(std::move(row));
  }

  /// A figure to 4 significant digits ("inf", "nan" as such).
  static std::string Number(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.4g", value);
    return text;
  }

 private:
  static int Width(const std::string& column) { return std::max<int>(18, int(column.size()) + 2); }

  std::vector<std::string> columns_;
  std::string csv_path_;
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace flagsim::lab
