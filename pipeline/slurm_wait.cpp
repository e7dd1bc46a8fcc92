// wait_for_jobs (pipeline/slurm_submit.h): poll squeue until every job and array task of the
// submitted chains has ended, then name what failed. A final state is remembered when first seen,
// so that Slurm forgetting a job later (MinJobAge) does not matter; a task that squeue never
// lists (an array task cancelled while pending leaves no record) counts as "no record".
#include <chrono>
#include <map>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "pipeline/process.h"
#include "pipeline/run.h"
#include "pipeline/slurm_submit.h"

namespace shatter {

namespace {

// One thing squeue reports on: a plain job, or one task of an array.
struct Unit {
    const SlurmJob* job;
    std::optional<uint32_t> task;
    std::string key() const { return task ? fmt::format("{}_{}", job->id, *task) : job->id; }
    std::string log() const {
        return task ? fmt::format("{}/{}-{}_{}.log", job->log_dir, job->kind, job->id, *task)
                    : fmt::format("{}/{}-{}.log", job->log_dir, job->kind, job->id);
    }
    std::string name() const {
        const std::string prefix = job->label.empty() ? "" : fmt::format("{}: ", job->label);
        if (job->kind == "simulate") return fmt::format("{}prescore/simulate job {}", prefix, job->id);
        if (!task) return fmt::format("{}{} job {}", prefix, job->kind, job->id);
        const auto [first, end] = chunk_frames(job->frames, *task, job->tasks);
        const std::string frames = end > first ? fmt::format(" (frames {}..{})", first, end - 1) : " (no frames)";
        return fmt::format("{}{} task {} of job {}{}", prefix, job->kind, *task, job->id, frames);
    }
};

std::vector<Unit> units_of(const std::vector<SlurmJob>& jobs) {
    std::vector<Unit> out;
    for (const SlurmJob& j : jobs) {
        if (j.id.empty()) continue;
        if (j.tasks == 0) out.push_back({&j, std::nullopt});
        for (uint32_t t = 0; t < j.tasks; ++t) out.push_back({&j, t});
    }
    return out;
}

// The status of `u` in squeue's records; nullopt when squeue has none.
std::optional<JobStatus> status_of(const Unit& u, const std::vector<JobStatus>& records) {
    for (const JobStatus& s : records) {
        if (s.job_id != u.job->id) continue;
        if (!u.task && !s.task && s.pending.empty()) return s;
        if (u.task && s.task == u.task) return s;
        if (u.task && std::find(s.pending.begin(), s.pending.end(), *u.task) != s.pending.end()) return s;
    }
    return std::nullopt;
}

// The log's last lines, indented, to show what the job said.
std::string log_tail(const std::string& path) {
    try {
        const std::string tail = last_lines(read_file(path, "job log"), 2);
        if (tail.empty()) return "";
        std::string out;
        size_t start = 0;
        while (start < tail.size()) {
            size_t end = tail.find('\n', start);
            if (end == std::string::npos) end = tail.size();
            out += "\n    " + tail.substr(start, end - start);
            start = end + 1;
        }
        return out;
    } catch (const Error&) {
        return "";
    }
}

}  // namespace

std::vector<std::string> wait_for_jobs(const std::vector<SlurmJob>& jobs, const SlurmSettings& settings,
                                       const std::function<void(const std::string&)>& on_change) {
    const std::vector<Unit> units = units_of(jobs);
    std::vector<std::string> ids;
    for (const SlurmJob& j : jobs)
        if (!j.id.empty()) ids.push_back(j.id);
    std::map<std::string, JobStatus> final_state;
    std::map<std::string, std::string> shown;
    std::map<std::string, int> missing_polls;
    const auto start = std::chrono::steady_clock::now();
    int squeue_failures = 0;
    for (;;) {
        std::vector<JobStatus> records;
        try {
            records = query_jobs(settings, ids);
            squeue_failures = 0;
        } catch (const Error& e) {
            // A busy controller times out now and then: a few failures in a row are tolerated.
            if (++squeue_failures >= 5) throw;
            spdlog::warn("{} (retrying)", e.what());
            std::this_thread::sleep_for(std::chrono::seconds(2 * squeue_failures));
            continue;
        }
        size_t open = 0;
        for (const Unit& u : units) {
            if (final_state.count(u.key())) continue;
            std::optional<JobStatus> s = status_of(u, records);
            if (!s) {
                // Not listed: cancelled before it started, or forgotten. Seen twice, it is final.
                if (++missing_polls[u.key()] < 2) { ++open; continue; }
                s = JobStatus{u.job->id, u.task, {}, "UNKNOWN", "no record in squeue: cancelled before it started, "
                                                                 "or ended more than MinJobAge ago", 0, 0};
                final_state[u.key()] = *s;
            } else if (s->finished()) {
                final_state[u.key()] = *s;
            } else {
                ++open;
            }
            const std::string line = s->state == "UNKNOWN" ? "no record in squeue"
                                     : s->finished()         ? s->state + ": " + s->describe()
                                                             : s->state;
            if (shown[u.key()] != line) on_change(u.name() + ": " + line), shown[u.key()] = line;
        }
        if (open == 0) break;
        // Every second at first, then less often (at most every 10 s) for long jobs.
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::this_thread::sleep_for(std::chrono::milliseconds(int(1000 * std::min(10.0, 1.0 + elapsed / 60))));
    }

    // The causes first, then what did not run because of them.
    std::vector<std::string> failed, not_run;
    for (const Unit& u : units) {
        const JobStatus& s = final_state.at(u.key());
        if (s.succeeded()) continue;
        if (s.reason.rfind("Dependency", 0) == 0)
            not_run.push_back(fmt::format("{} did not run: a job it waits for failed", u.name()));
        else if (s.state == "UNKNOWN")
            failed.push_back(fmt::format("{} failed: {}; log: {}", u.name(), s.reason, u.log()));
        else
            failed.push_back(fmt::format("{} failed: {}; log: {}{}", u.name(), s.describe(), u.log(), log_tail(u.log())));
    }
    failed.insert(failed.end(), not_run.begin(), not_run.end());
    return failed;
}

}  // namespace shatter
