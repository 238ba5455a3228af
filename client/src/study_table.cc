#include "study_table.h"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "job_text.h"

namespace dlmfd::cli {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TableCell Number(double x) { return std::isnan(x) ? TableCell{} : TableCell{x}; }

TableCell ParameterCell(const v1::Parameter& p) {
  switch (p.value_case()) {
    case v1::Parameter::kIntValue:
      return p.int_value();
    case v1::Parameter::kDoubleValue:
      return Number(p.double_value());
    case v1::Parameter::kBoolValue:
      return p.bool_value();
    case v1::Parameter::kTextValue:
      return p.text_value();
    default:
      return {};
  }
}

const char* const kParticleColumns[] = {"radius", "x",  "y",  "angle",  "u",         "v",
                                        "omega",  "fx", "fy", "torque", "fall_speed"};

std::vector<TableCell> ParticleCells(const v1::ParticleRow& q) {
  return {Number(q.radius()),
          Number(q.x()),
          Number(q.y()),
          Number(q.angle()),
          Number(q.u()),
          Number(q.v()),
          Number(q.angular_velocity()),
          Number(q.force_x()),
          Number(q.force_y()),
          Number(q.torque()),
          Number(q.fall_speed())};
}

std::string CellText(const TableCell& cell) {
  if (const auto* i = std::get_if<int64_t>(&cell)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&cell)) {
    if (std::isinf(*d)) return *d > 0 ? "inf" : "-inf";
    char text[40];
    const auto end = std::to_chars(text, text + sizeof text, *d).ptr;  // shortest round trip
    return std::string(text, end);
  }
  if (const auto* b = std::get_if<bool>(&cell)) return *b ? "true" : "false";
  if (const auto* s = std::get_if<std::string>(&cell)) return *s;
  return "";
}

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

size_t StudyTable::Column(const std::string& name, const std::string& flag) const {
  for (size_t k = 0; k < columns.size(); ++k) {
    if (columns[k] == name) return k;
  }
  std::string names;
  for (const std::string& c : columns) names += (names.empty() ? "" : ", ") + c;
  throw UsageError(flag + " " + name + ": no such column; the table has " + names);
}

StudyTable StudyTable::Select(const std::vector<std::string>& names) const {
  StudyTable out;
  std::vector<size_t> index;
  for (const std::string& n : names) index.push_back(Column(n, "--columns"));
  out.columns = names;
  for (const auto& row : rows) {
    std::vector<TableCell> cells;
    for (size_t k : index) cells.push_back(row[k]);
    out.rows.push_back(std::move(cells));
  }
  return out;
}

grpc::Status FetchTableRows(Connection& connection, const std::string& study_id,
                            const std::vector<std::string>& job_ids, v1::TableResponse* out) {
  auto context = connection.UnaryContext();
  v1::TableRequest request;
  request.set_study_id(study_id);
  for (const std::string& id : job_ids) request.add_job_ids(id);
  return connection.jobs().Table(context.get(), request, out);
}

StudyTable FlattenTable(const v1::TableResponse& response) {
  StudyTable t;
  std::vector<std::string> keys;
  std::map<std::string, size_t> key_index;
  size_t particles = 0;
  for (const v1::TableRow& row : response.rows()) {
    for (const v1::Parameter& p : row.parameters()) {
      if (key_index.emplace(p.key(), keys.size()).second) keys.push_back(p.key());
    }
    particles = std::max(particles, static_cast<size_t>(row.particles_size()));
  }
  t.columns = {"job", "name", "state"};
  t.columns.insert(t.columns.end(), keys.begin(), keys.end());
  for (const char* c : {"status", "reason", "steps", "time", "wall_seconds", "fall_speed",
                        "min_gap", "min_wall_gap", "max_trA", "min_eig_A", "Re", "De", "E", "M"}) {
    t.columns.push_back(c);
  }
  for (size_t p = 0; p < particles; ++p) {
    for (const char* c : kParticleColumns) t.columns.push_back("p" + std::to_string(p) + "." + c);
  }
  for (const v1::TableRow& row : response.rows()) {
    std::vector<TableCell> cells = {row.job_id(), row.name(), StateName(row.state())};
    std::vector<TableCell> parameters(keys.size());
    for (const v1::Parameter& p : row.parameters())
      parameters[key_index[p.key()]] = ParameterCell(p);
    cells.insert(cells.end(), parameters.begin(), parameters.end());
    if (row.has_summary()) {
      for (TableCell c : {TableCell{row.status()}, TableCell{row.reason()}, TableCell{row.steps()},
                          Number(row.time()), Number(row.wall_seconds()), Number(row.fall_speed()),
                          Number(row.min_gap()), Number(row.min_wall_gap()), Number(row.max_tra()),
                          Number(row.min_eig_a()), Number(row.reynolds()), Number(row.deborah()),
                          Number(row.elasticity()), Number(row.mach())}) {
        cells.push_back(std::move(c));
      }
    } else {
      cells.resize(cells.size() + 14);
    }
    for (size_t p = 0; p < particles; ++p) {
      if (p < static_cast<size_t>(row.particles_size())) {
        for (TableCell& c : ParticleCells(row.particles(static_cast<int>(p)))) cells.push_back(c);
      } else {
        cells.resize(cells.size() + std::size(kParticleColumns));
      }
    }
    t.rows.push_back(std::move(cells));
  }
  return t;
}

std::string TableCsv(const StudyTable& table) {
  std::string out;
  for (size_t k = 0; k < table.columns.size(); ++k) {
    out += (k ? "," : "") + CsvField(table.columns[k]);
  }
  out += "\n";
  for (const auto& row : table.rows) {
    for (size_t k = 0; k < row.size(); ++k) out += (k ? "," : "") + CsvField(CellText(row[k]));
    out += "\n";
  }
  return out;
}

std::string TableJson(const StudyTable& table) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const auto& row : table.rows) {
    nlohmann::ordered_json object = nlohmann::ordered_json::object();
    for (size_t k = 0; k < row.size(); ++k) {
      const TableCell& cell = row[k];
      nlohmann::ordered_json& value = object[table.columns[k]];
      if (const auto* i = std::get_if<int64_t>(&cell)) {
        value = *i;
      } else if (const auto* d = std::get_if<double>(&cell)) {
        value = *d;  // infinities become null (JSON has none)
      } else if (const auto* b = std::get_if<bool>(&cell)) {
        value = *b;
      } else if (const auto* s = std::get_if<std::string>(&cell)) {
        value = *s;
      }
    }
    rows.push_back(std::move(object));
  }
  return rows.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

double CellNumber(const TableCell& cell) {
  if (const auto* i = std::get_if<int64_t>(&cell)) return static_cast<double>(*i);
  if (const auto* d = std::get_if<double>(&cell)) return *d;
  if (const auto* b = std::get_if<bool>(&cell)) return *b ? 1.0 : 0.0;
  return kNaN;
}

}  // namespace dlmfd::cli
