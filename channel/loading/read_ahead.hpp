#pragma once
// The channel's read-ahead: the interpreter runs on a thread of its own, at normal priority,
// and hands its commands to the cycle through a fixed-capacity single-producer/single-consumer
// ring (issue 23; decision 66). The cycle only takes what is there: it never waits for the
// interpreter, never allocates for it and never touches a program file.
//
// What the interpreter evaluates stays what it evaluates when the cycle pulls each command
// itself:
// - A read-ahead stop (a command with `barrier`: G04.1, G140-G142, G144/G145, M00/M01/M30,
//   G53, #3006, M18, G31 and the others of spec dafeng §4.3) ends the producer's reading: it
//   waits until the cycle has pulled past it, and takes then the position the channel adopted
//   there and a G31's result.
// - The channel's own writes to the shared variables travel in the ring, in program order, and
//   reach `writes_out` as the cycle takes the commands after them, in the cycle they would have
//   been evaluated in.
// - The partners' writes to the shared variables reach the interpreter at read-ahead stops and
//   at starts, never between (the visibility rule of ARCHITECTURE.md §5), so that what a
//   program reads does not depend on how far ahead the thread was.
// In lockstep the cycle waits for the commands it pulls (the run is then the same, cycle for
// cycle, however fast the thread is); in realtime it takes what is ready and pulls the rest in
// later cycles, as a control whose buffer ran empty does.
#include "channel/interp/command_source.hpp"
#include "channel/interp/interp_config.hpp"
#include "channel/interp/macro/variable_store.hpp"
#include "common/cycle/spsc_ring.hpp"

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <thread>
#include <utility>

namespace mcnc::channel {

class ReadAhead final : public interp::CommandSource {
 public:
  // Commands (and the shared writes between them) read ahead at most: the memory a program of
  // any length takes in the ring.
  static constexpr std::size_t kWindow = 256;
  // Partners' writes held between two read-ahead stops.
  static constexpr std::size_t kPeerWrites = 4096;

  // `writes_out`: where this channel's own writes to the shared variables go, on the cycle's
  // thread (null: nowhere). `shared`: the machine's shared variables that the interpreter
  // reads, where the partners' writes go (null: none).
  ReadAhead(interp::macro::SharedWriteSink* writes_out, interp::macro::VariableStore* shared);
  ~ReadAhead() override;
  ReadAhead(const ReadAhead&) = delete;
  ReadAhead& operator=(const ReadAhead&) = delete;

  // The sink that the interpreter behind this read-ahead must tell its shared writes to
  // (InterpreterConfig::shared_sink): its calls come on the read-ahead thread.
  [[nodiscard]] interp::macro::SharedWriteSink& interpreter_sink() noexcept { return relay_; }
  // Starts the read-ahead thread over `inner`, which from then on only that thread touches.
  void start(interp::CommandSource& inner);
  // Lockstep: ready() waits for the command the cycle pulls. Realtime (the default): it does
  // not.
  void set_lockstep(bool lockstep) noexcept { lockstep_ = lockstep; }
  // Ends the thread (it stops reading at its next command) and applies the partners' writes
  // it had not applied yet. The source then answers nothing more.
  void stop() noexcept;

  // A partner's write to a shared variable, from the cycle's thread. False when kPeerWrites are
  // held already (the caller counts it lost).
  bool peer_write(std::int64_t number, interp::macro::MacroValue value) noexcept;

  // CommandSource, from the cycle's thread. A start (rewind, start_mdi, call) abandons what
  // was read ahead of an earlier run; call() and start_mdi() answer nullopt, and an alarm of
  // theirs is the first pull's answer.
  void rewind(const interp::AxisVector& current) override;
  [[nodiscard]] bool ready() noexcept override;
  std::optional<interp::PullResult> next() override;
  // In its slot of the ring, which goes back to the thread at the next call of ready().
  const interp::PullResult* take() override { return take_slot(); }
  [[nodiscard]] std::size_t block_count() const noexcept override { return block_count_; }
  void adopt_position(const interp::AxisVector& at) override;
  void skip_result(bool skipped, const interp::AxisVector& skip_at,
                   const interp::AxisVector& stop_at) override;
  void multi_skip_result(std::span<const double> latched,
                         const interp::AxisVector& stop_at) override;
  void load_timer_result(std::uint32_t axes) override;
  void overload_result(std::uint32_t overloads, std::uint64_t dropped_block,
                       const interp::AxisVector& stop_at) override;
  std::optional<interp::ProgramAlarm> call(int number, std::span<const std::pair<int, double>> args,
                                           const interp::AxisVector& current) override;
  std::optional<interp::ProgramAlarm> start_mdi(const interp::AxisVector& current) override;
  void adopt(interp::CheckedProgram program) noexcept override;
  void prepare_mdi(interp::CheckedProgram blocks) noexcept override;
  [[nodiscard]] bool has_program() const noexcept override { return has_program_; }
  void abandon() noexcept override;

 private:
  struct SharedWrite {
    std::int64_t number = 0;
    interp::macro::MacroValue value;
  };
  // One slot of the ring from the thread to the cycle.
  struct Entry {
    enum class Kind : std::uint8_t { pulled, exhausted, shared_write, started };
    Kind kind = Kind::pulled;
    std::uint64_t run = 0;  // the start it belongs to: older ones are dropped
    interp::PullResult pulled;
    SharedWrite write;
    std::size_t block_count = 0;  // started: of the run
  };
  // One order from the cycle to the thread.
  struct Order {
    enum class Kind : std::uint8_t { rewind, mdi, call, resume, adopt, prepare_mdi, stop };
    Kind kind = Kind::resume;
    std::uint64_t run = 0;
    interp::AxisVector at{};
    bool has_position = false;
    bool has_skip = false;  // a G31's result, after the position
    bool skipped = false;
    interp::AxisVector skip_at{};
    interp::AxisVector stop_at{};
    bool multi_skip = false;  // the result is a G31.8's: these positions
    std::array<double, interp::kMaxMultiSkipSignals> latched{};
    std::size_t latched_count = 0;
    bool has_timer = false;  // a G10 L14 P20-P51's result: these axes met it
    std::uint32_t timer_axes = 0;
    bool has_overload = false;  // a G10 L14 P7/P8 in-feed's result (stop_at if dropped)
    std::uint32_t overloads = 0;
    std::uint64_t dropped_block = 0;
    int program = 0;
    std::array<std::pair<int, double>, interp::kSubcallArgs> args{};
    std::size_t arg_count = 0;
    std::uint64_t peer_writes = 0;  // partners' writes to apply first: this many in all
    interp::CheckedProgram checked;
  };
  // The interpreter's shared writes, into the ring (the read-ahead thread's).
  class Relay final : public interp::macro::SharedWriteSink {
   public:
    explicit Relay(ReadAhead& owner) : owner_(owner) {}
    void on_shared_write(std::int64_t number, interp::macro::MacroValue value) noexcept override;

   private:
    ReadAhead& owner_;
  };

  // Cycle side.
  // The next answer where it lies (a slot of the ring, or answer_), handed over; nullptr when
  // nothing is left.
  interp::PullResult* take_slot();
  // The slot take() handed over goes back to the thread.
  void release_taken() noexcept;
  // Gives the front slot back; wakes the thread only when it may wait for that room.
  void pop_entry() noexcept;
  void ring_bell() noexcept;
  // The thread stands (a stop, the end, an alarm, no run): what partners wrote may reach it.
  void thread_stands() noexcept;
  // The next order's slot; nullptr (and the alarm) when the queue is full.
  Order* order_slot() noexcept;
  void post() noexcept;
  // A new run: what was read ahead for earlier ones is dropped. Its order's slot, to fill.
  Order* begin_run(Order::Kind kind, const interp::AxisVector& at) noexcept;
  // The thread.
  void run_thread() noexcept;
  void apply_peer_writes(std::uint64_t upto) noexcept;
  void handle(Order& order) noexcept;
  void read_until_stop() noexcept;
  // Waits for room in the ring; false when the thread must stop reading (a newer run, stop).
  Entry* room() noexcept;
  [[nodiscard]] bool abandoned() const noexcept;

  interp::macro::SharedWriteSink* writes_out_;
  interp::macro::VariableStore* shared_;
  Relay relay_{*this};
  interp::CommandSource* inner_ = nullptr;
  std::thread thread_;
  bool lockstep_ = false;

  cycle::SpscRing<Entry, kWindow> entries_;
  cycle::SpscRing<Order, 16> orders_;
  cycle::SpscRing<SharedWrite, kPeerWrites> peer_writes_;
  // The thread waits on this for orders and for room; the cycle adds 1 to wake it.
  std::atomic<std::uint32_t> bell_{0};
  std::atomic<std::uint64_t> latest_run_{0};  // the newest start the cycle posted
  // Partners' writes the thread may apply while it is not reading (idle, or parked at a stop):
  // those posted while the cycle expected nothing of it, so never one posted after an order
  // that made it read on.
  std::atomic<std::uint64_t> visible_writes_{0};
  std::atomic<bool> stopping_{false};

  // The cycle's own state.
  std::uint64_t run_ = 0;
  bool expecting_ = false;    // the thread is reading for the cycle: waiting for it ends
  bool passed_stop_ = false;  // the last command taken stopped the read-ahead: resume it
  bool has_position_ = false;
  interp::AxisVector position_{};
  bool has_skip_ = false;  // skip_result() waits for the resume
  bool skipped_ = false;
  interp::AxisVector skip_at_{};
  interp::AxisVector stop_at_{};
  bool multi_skip_ = false;
  std::array<double, interp::kMaxMultiSkipSignals> latched_{};
  std::size_t latched_count_ = 0;
  bool has_timer_ = false;  // load_timer_result() waits for the resume
  std::uint32_t timer_axes_ = 0;
  bool has_overload_ = false;  // overload_result() waits for the resume
  std::uint32_t overloads_ = 0;
  std::uint64_t dropped_block_ = 0;
  std::uint64_t peer_writes_posted_ = 0;
  std::size_t block_count_ = 0;
  bool has_program_ = false;
  bool stopped_ = false;
  bool order_lost_ = false;   // an order did not fit: the next pull is an alarm
  bool holds_taken_ = false;  // the front slot was handed over by take() and is not popped yet
  std::optional<interp::PullResult> answer_;  // an answer of the read-ahead's own (an alarm)

  // The thread's own state.
  std::uint64_t thread_run_ = 0;
  bool reading_ = false;
  std::uint64_t peer_writes_applied_ = 0;
};

}  // namespace mcnc::channel
