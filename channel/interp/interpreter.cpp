#include "channel/interp/interpreter.hpp"

#include "channel/interp/program_run.hpp"

namespace mcnc::interp {

Interpreter::Interpreter(const InterpreterConfig& config, const InterpreterEnvironment* environment)
    : run_(std::make_unique<ProgramRun>(config, environment)) {}

Interpreter::~Interpreter() = default;

std::optional<ProgramAlarm> Interpreter::start(std::string text, const std::string& file_name) {
  return run_->start_text(std::move(text), file_name);
}

std::optional<ProgramAlarm> Interpreter::start_file(const std::string& path,
                                                    const std::string& file_name) {
  return run_->start_file(path, file_name);
}

std::optional<ProgramAlarm> Interpreter::start_number(int number) {
  return run_->start_number(number);
}

std::optional<ProgramAlarm> Interpreter::start_called(
    int number, std::span<const std::pair<int, double>> args) {
  return run_->start_called(number, args);
}

std::optional<ProgramAlarm> Interpreter::start_mdi(std::string text) {
  return run_->start_mdi(std::move(text));
}

std::optional<InterpResult> Interpreter::next() {
  return run_->next();
}

std::vector<ProgramAlarm> Interpreter::take_warnings() {
  return run_->take_warnings();
}

macro::VariableStore& Interpreter::variables() {
  return run_->variables();
}

AxisVector Interpreter::machine_position() const {
  return run_->machine();
}

void Interpreter::set_machine_position(const AxisVector& at) {
  run_->set_machine(at);
}

void Interpreter::skip_result(bool skipped, const AxisVector& skip_at, const AxisVector& stop_at) {
  run_->set_skip_result(skipped, skip_at, stop_at);
}

void Interpreter::load_timer_result(std::uint32_t axes) {
  run_->set_load_timer_result(axes);
}

void Interpreter::overload_result(std::uint32_t overloads, std::uint64_t dropped_block,
                                  const AxisVector& stop_at) {
  run_->set_overload_result(overloads, dropped_block, stop_at);
}

void Interpreter::multi_skip_result(std::span<const double> latched, const AxisVector& stop_at) {
  run_->set_multi_skip_result(latched, stop_at);
}

double Interpreter::program_position(int axis) const {
  return run_->program_position(axis);
}

std::size_t Interpreter::main_block_count() const {
  return run_->main_block_count();
}

std::optional<ProgramAlarm> Interpreter::save_retained() {
  return run_->save_retained();
}

}  // namespace mcnc::interp
