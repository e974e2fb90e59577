// SPDX-License-Identifier: MIT
// jacobid record: receives the controller's estimate stream (UDP, docs/stream-format.md) and writes the
// CSV log that `jacobid identify` reads, reporting every datagram that did not become a row.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <memory>

#include "cli/command.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "core/same_file.hpp"
#include "stream/recorder.hpp"
#include "stream/udp_receiver.hpp"

namespace jacobid::cli {
namespace {

struct RecordOptions {
    std::string udp;
    std::string output;
    std::string summary;
    std::string on_gap = "error";
    std::uint64_t count = 0;
    double duration = 0.0;
    double idle_timeout = 0.0;
    std::size_t reorder_window = 32;
    bool estimates = false;
    bool quiet = false;
};

volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void on_stop_signal(int signal) { g_stop_signal = signal; }

// SIGINT/SIGTERM end the recording cleanly (files flushed, summary written) instead of killing us
// mid-write. No SA_RESTART, so the signal also wakes the poll() we are sleeping in.
class StopSignals {
public:
    StopSignals() {
        g_stop_signal = 0;
        struct sigaction action{};
        action.sa_handler = on_stop_signal;
        sigemptyset(&action.sa_mask);
        sigaction(SIGINT, &action, &old_int_);
        sigaction(SIGTERM, &action, &old_term_);
    }
    ~StopSignals() {
        sigaction(SIGINT, &old_int_, nullptr);
        sigaction(SIGTERM, &old_term_, nullptr);
    }
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;

private:
    struct sigaction old_int_{};
    struct sigaction old_term_{};
};

// With --on-gap split the recorder also writes OUT's stem.N.ext beside it (stream/recorder.hpp): the summary
// must not be one of them (it would be written over the segment, or the segment over it).
void refuse_summary_among_segments(const RecordOptions& o) {
    if (o.summary.empty() || o.on_gap != "split") return;
    const std::filesystem::path out(o.output), summary(o.summary);
    const std::string stem = out.stem().string() + ".", name = summary.stem().string();
    const bool numbered = name.size() > stem.size() && name.compare(0, stem.size(), stem) == 0 &&
                          name.find_first_not_of("0123456789", stem.size()) == std::string::npos;
    const auto folder = [](const std::filesystem::path& p) { return p.parent_path().empty() ? std::filesystem::path(".") : p.parent_path(); };
    if (numbered && summary.extension() == out.extension() && same_file(folder(summary), folder(out))) {
        throw InputError(fmt::format("--summary {}: --on-gap split may write this file as a segment of --out {} ({}N{}); give the summary another name",
                                     o.summary, o.output, stem, out.extension().string()));
    }
}

void run(const RecordOptions& o) {
    check_outputs({{"--out", o.output}, {"--summary", o.summary}});
    refuse_summary_among_segments(o);
    const stream::GapPolicy policy = stream::parse_gap_policy(o.on_gap);
    if (o.duration < 0.0 || o.idle_timeout < 0.0) throw InputError("--duration / --idle-timeout: seconds must be >= 0 (0 = no limit)");
    const stream::Endpoint endpoint = stream::parse_endpoint(o.udp, "--udp");
    stream::UdpReceiver receiver(endpoint);
    stream::Recorder recorder({o.output, policy, o.estimates, o.reorder_window});
    StopSignals signals;
    // Tests and scripts wait for this line before sending (with port 0 it is the only way to learn the port).
    fmt::print(stderr, "record: listening on {}:{}\n", receiver.address(), receiver.port());

    using Clock = std::chrono::steady_clock;
    const auto seconds_since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
    const Clock::time_point start = Clock::now();
    Clock::time_point last_datagram = start, last_progress = start;
    std::vector<std::uint8_t> buffer;
    buffer.reserve(65536);  // any UDP payload fits; larger would be reported as oversized
    std::string stop_reason;
    while (stop_reason.empty()) {
        std::size_t full_size = 0;
        if (receiver.receive(buffer, full_size, 50)) {
            recorder.datagram(buffer, full_size);
            last_datagram = Clock::now();
            if (o.count > 0 && recorder.received() >= o.count) stop_reason = fmt::format("{} datagrams received (--count)", o.count);
        }
        if (g_stop_signal != 0) stop_reason = g_stop_signal == SIGINT ? "interrupted (SIGINT)" : "terminated (SIGTERM)";
        if (o.duration > 0.0 && seconds_since(start) >= o.duration) stop_reason = fmt::format("{} s elapsed (--duration)", o.duration);
        if (o.idle_timeout > 0.0 && seconds_since(last_datagram) >= o.idle_timeout) {
            stop_reason = fmt::format("no datagram for {} s (--idle-timeout)", o.idle_timeout);
        }
        if (!o.quiet && seconds_since(last_progress) >= 1.0) {
            last_progress = Clock::now();
            fmt::print(stderr, "{}\n", recorder.progress_line(seconds_since(start)));
        }
    }
    recorder.finish();

    nlohmann::json summary = recorder.summary();
    summary["endpoint"] = fmt::format("{}:{}", receiver.address(), receiver.port());
    summary["stopped"] = stop_reason;
    summary["seconds"] = seconds_since(start);
    if (!o.summary.empty()) write_output(o.summary, summary.dump(2) + "\n");  // the close is checked (a full disk)
    const auto& c = recorder.tracker().counts();
    fmt::print(stderr, "record: stopped: {}\n", stop_reason);
    fmt::print(stderr, "record: {} datagrams received, {} rows written, {} lost, {} late, {} duplicated, {} reordered, {} malformed\n",
               recorder.received(), recorder.rows_written(), recorder.tracker().lost_count(), c.late, c.duplicated, c.reordered,
               recorder.malformed());
    for (const auto& f : recorder.files()) {
        fmt::print(stderr, "record: {}: {} rows (sequence {}..{})\n", f.path, f.rows, f.first_sequence, f.last_sequence);
    }
    for (const std::string& w : recorder.warnings()) fmt::print(stderr, "record: warning: {}\n", w);
    if (recorder.rows_written() == 0) {
        throw InputError(fmt::format("--udp {}: no usable estimate datagram received ({} received, {} malformed); nothing written",
                                     summary["endpoint"].get<std::string>(), recorder.received(), recorder.malformed()));
    }
    const std::vector<std::string> holes = recorder.holes();
    for (const std::string& h : holes) fmt::print(stderr, "record: {}: {}\n", policy == stream::GapPolicy::Error ? "hole" : "note", h);
    if (policy == stream::GapPolicy::Error && !holes.empty()) {
        std::string all;
        for (const std::string& h : holes) all += (all.empty() ? "" : "; ") + h;
        throw InputError(fmt::format("{} is incomplete: {} (rows received were written; --on-gap split or mark accepts holes)", o.output, all));
    }
}

}  // namespace

void add_record_command(CLI::App& app) {
    auto o = std::make_shared<RecordOptions>();
    CLI::App* cmd = app.add_subcommand("record", "record the controller's UDP estimate stream into a CSV log for `jacobid identify`");
    cmd->add_option("--udp", o->udp, "HOST:PORT to listen on, e.g. 0.0.0.0:5005 (port 0 = any free port, printed on stderr)")->required();
    cmd->add_option("--out,-o", o->output, "CSV log: t,q1..qn,tau1..taun[,estimates],seq,stream_flags,flags1..n")->required()->check(file_path());
    cmd->add_option("--summary", o->summary, "also write the summary (counts, lost/late/unmeasured sequence numbers, files) as JSON")->check(file_path());
    cmd->add_option("--count", o->count, "stop after this many datagrams (any, malformed included); 0 = no limit")
        ->check(whole_number_from(0))
        ->capture_default_str();
    cmd->add_option("--duration", o->duration, "stop after this many seconds; 0 = no limit")->check(non_negative_number())->capture_default_str();
    cmd->add_option("--idle-timeout", o->idle_timeout, "stop when no datagram arrived for this many seconds; 0 = no limit")
        ->check(non_negative_number())
        ->capture_default_str();
    cmd->add_option("--on-gap", o->on_gap,
                    "lost/late datagrams, stale rows, restarts: error = write what arrived and exit 2 naming them; "
                    "split = new file at each hole (log.csv, log.2.csv, ...); mark = one file, exit 0")
        ->check(CLI::IsMember({"error", "split", "mark"}))
        ->capture_default_str();
    cmd->add_option("--reorder-window", o->reorder_window, "datagrams held back to undo reordering before a missing one is given up")
        ->check(whole_number_in(0, 1e6))
        ->capture_default_str();
    cmd->add_flag("--estimates", o->estimates, "also write the controller's estimates q<j>_hat, qd<j>_hat, qdd<j>_hat");
    cmd->add_flag("--quiet", o->quiet, "no progress line every second");
    cmd->footer("Stops on --count, --duration, --idle-timeout or Ctrl-C (SIGINT), whichever comes first; files are flushed in every case.");
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
