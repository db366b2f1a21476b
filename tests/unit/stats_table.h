// A stats CSV as `dynamesh-cli run --stats` writes it (core/io/stats_csv.cpp), read whole for
// the end-to-end tests: a header of column names, then one row per step, row 0 being the
// initial adaptation. Every cell is a number, so a plain comma split is the whole format.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace dynamesh::test {

inline std::vector<std::string> split_cells(const std::string& line, char separator = ',') {
  std::vector<std::string> cells;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, separator);) cells.push_back(cell);
  return cells;
}

class StatsTable {
 public:
  // Fails the test when a row's width differs from the header's (a torn or misquoted file).
  explicit StatsTable(const std::filesystem::path& csv) {
    std::ifstream in(csv);
    std::string line;
    if (!std::getline(in, line)) {
      ADD_FAILURE() << "no header in " << csv;
      return;
    }
    names_ = split_cells(line);
    while (std::getline(in, line)) {
      rows_.push_back(split_cells(line));
      EXPECT_EQ(rows_.back().size(), names_.size()) << csv << ": " << line;
    }
  }

  std::size_t rows() const { return rows_.size(); }
  const std::vector<std::string>& names() const { return names_; }

  // The cell of column `name` in row `row` ("" and a test failure when either is missing).
  std::string cell(std::size_t row, const std::string& name) const {
    const std::size_t c = index(name);
    if (row >= rows_.size() || c >= rows_[row].size()) {
      if (c < names_.size()) ADD_FAILURE() << "no cell " << name << " in row " << row;
      return "";
    }
    return rows_[row][c];
  }

  double number(std::size_t row, const std::string& name) const {
    const std::string text = cell(row, name);
    return text.empty() ? std::nan("") : std::stod(text);
  }

  // One column, a cell per step.
  std::vector<std::string> column(const std::string& name) const {
    std::vector<std::string> cells;
    if (index(name) == names_.size()) return cells;
    for (std::size_t row = 0; row < rows_.size(); ++row) cells.push_back(cell(row, name));
    return cells;
  }

 private:
  // The column's position; names().size() and a test failure when there is no such column.
  std::size_t index(const std::string& name) const {
    const auto at =
        static_cast<std::size_t>(std::find(names_.begin(), names_.end(), name) - names_.begin());
    if (at == names_.size()) ADD_FAILURE() << "no column " << name;
    return at;
  }

  std::vector<std::string> names_;
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace dynamesh::test
