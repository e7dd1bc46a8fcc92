#include "pipeline/slurm.h"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

#include "core/error.h"
#include "pipeline/process.h"

namespace shatter {

namespace {

std::string trim(const std::string& s) {
    size_t a = 0, b = s.size();
    while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
    while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
    return s.substr(a, b - a);
}

bool all_digits(const std::string& s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::string find_client(const std::string& program) {
    const std::optional<std::string> path = find_program(program);
    if (!path) throw_missing_slurm_client(program);
    return *path;
}

// What a client said, for an error message.
std::string client_output(const ProcessResult& r) {
    const std::string said = last_lines(r.err + "\n" + r.out, 3);
    return said.empty() ? r.describe() : said;
}

// "0-3", "1,3-5", "0-15:4", "0-3%2" (a pending array's remaining tasks) as indices.
std::vector<uint32_t> parse_task_ranges(std::string text) {
    std::vector<uint32_t> out;
    if (const size_t pct = text.find('%'); pct != std::string::npos) text.resize(pct);
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find(',', start);
        if (end == std::string::npos) end = text.size();
        const std::string part = text.substr(start, end - start);
        unsigned a = 0, b = 0, step = 1;
        if (std::sscanf(part.c_str(), "%u-%u:%u", &a, &b, &step) >= 2 && step > 0) {
            for (unsigned i = a; i <= b && out.size() < 1000000; i += step) out.push_back(i);
        } else if (all_digits(part)) {
            out.push_back(uint32_t(std::stoul(part)));
        }
        start = end + 1;
    }
    return out;
}

// "FAILED", also from "CANCELLED by 0" or "CANCELLED+".
std::string base_state(const std::string& s) {
    size_t n = 0;
    while (n < s.size() && (std::isupper(static_cast<unsigned char>(s[n])) || s[n] == '_')) ++n;
    return s.substr(0, n);
}

}  // namespace

[[noreturn]] void throw_missing_slurm_client(const std::string& program) {
    throw Error(ExitCode::Tool, fmt::format("{}: not found on PATH: the Slurm clients are needed to submit to a cluster "
                                            "(fix: run on a login node of the cluster, or apt-get install slurm-client; "
                                            "for a local test cluster: make deps and scripts/slurm-local.sh start)",
                                            program));
}

std::string slurm_output_path(const std::string& path, const std::string& where) {
    if (path.find('\\') != std::string::npos)
        throw Error(ExitCode::Usage,
                    fmt::format("{}: {}: Slurm cannot write job logs into a path with a backslash (sbatch --output drops "
                                "every backslash and would write somewhere else) (fix: an output folder without '\\')",
                                where, path));
    std::string out;
    for (char c : path) out += c == '%' ? std::string("%%") : std::string(1, c);
    return out;
}

std::vector<std::string> sbatch_argv(const SlurmSettings& s, const JobRequest& job) {
    std::vector<std::string> argv = {s.sbatch, "--parsable", "--job-name=" + job.name, "--chdir=" + job.workdir,
                                     "--output=" + job.log};
    if (!job.array.empty()) argv.push_back("--array=" + job.array);
    if (!job.after_ok.empty()) {
        std::string dep = "--dependency=afterok";
        for (const std::string& id : job.after_ok) dep += ":" + id;
        argv.push_back(dep);
        argv.push_back("--kill-on-invalid-dep=yes");
    }
    if (!s.partition.empty()) argv.push_back("--partition=" + s.partition);
    if (!s.account.empty()) argv.push_back("--account=" + s.account);
    if (!s.time.empty()) argv.push_back("--time=" + s.time);
    if (!s.mem.empty()) argv.push_back("--mem=" + s.mem);
    if (s.cpus > 0) argv.push_back("--cpus-per-task=" + std::to_string(s.cpus));
    argv.insert(argv.end(), s.extra_args.begin(), s.extra_args.end());
    argv.push_back(job.script);
    argv.insert(argv.end(), job.args.begin(), job.args.end());
    return argv;
}

std::string submit_job(const SlurmSettings& settings, const JobRequest& job) {
    std::vector<std::string> argv = sbatch_argv(settings, job);
    argv[0] = find_client(settings.sbatch);
    const ProcessResult r = run_process(argv);
    if (!r.ok()) {
        const std::string said = client_output(r);
        const bool no_cluster = said.find("configuration source") != std::string::npos ||
                                said.find("Unable to contact slurm controller") != std::string::npos;
        const std::string fix = no_cluster ? "run on a login node of the cluster, or set SLURM_CONF to the cluster's "
                                             "slurm.conf (the local test cluster: eval \"$(scripts/slurm-local.sh env)\")"
                                           : "check --partition, --account, --time, --mem, --cpus and --sbatch-arg "
                                             "against the cluster: sinfo, sacctmgr show assoc";
        throw Error(ExitCode::Tool, fmt::format("sbatch: refused job {}: {} (fix: {}; the call was: {})", job.name, said,
                                                fix, command_line(argv)));
    }
    // --parsable prints "ID" or "ID;CLUSTER".
    const std::string first = trim(last_lines(r.out, 1));
    const std::string id = first.substr(0, first.find(';'));
    if (!all_digits(id))
        throw Error(ExitCode::Tool, fmt::format("sbatch: job {}: expected a job id from --parsable, got '{}' (fix: "
                                                "check the Slurm version; shatter needs sbatch --parsable)",
                                                job.name, first));
    return id;
}

bool JobStatus::finished() const {
    static const char* const kFinal[] = {"COMPLETED", "FAILED",   "CANCELLED", "TIMEOUT",  "NODE_FAIL",
                                         "OUT_OF_MEMORY", "BOOT_FAIL", "DEADLINE", "PREEMPTED"};
    const std::string s = base_state(state);
    return std::any_of(std::begin(kFinal), std::end(kFinal), [&](const char* f) { return s == f; });
}

bool JobStatus::succeeded() const { return base_state(state) == "COMPLETED" && exit_code == 0 && signal == 0; }

std::string JobStatus::describe() const {
    const std::string s = base_state(state);
    const std::string why = reason.empty() || reason == "None" ? "" : " (" + reason + ")";
    if (s == "COMPLETED" && exit_code == 0) return "completed";
    if (s == "CANCELLED") {
        if (reason.rfind("Dependency", 0) == 0) return "cancelled: a job it waits for failed";
        return "cancelled" + why;
    }
    if (s == "TIMEOUT") return "time limit reached (fix: a longer --time)";
    if (s == "OUT_OF_MEMORY") return "out of memory (fix: a larger --mem)";
    if (s == "NODE_FAIL") return "its node failed" + why;
    if (signal != 0) return fmt::format("killed by signal {}", signal);
    if (exit_code != 0) return fmt::format("exit code {}", exit_code);
    std::string lower = s;
    for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
    std::replace(lower.begin(), lower.end(), '_', ' ');
    return lower + why;
}

std::vector<JobStatus> parse_squeue(const std::string& text) {
    std::vector<JobStatus> out;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(start, end - start);
        start = end + 1;
        std::vector<std::string> f;
        size_t a = 0;
        for (size_t bar; (bar = line.find('|', a)) != std::string::npos; a = bar + 1) f.push_back(trim(line.substr(a, bar - a)));
        if (f.size() < 6 || !all_digits(f[0])) continue;
        JobStatus j;
        const bool array = all_digits(f[1]) && f[2] != "N/A" && !f[2].empty();
        j.job_id = array ? f[1] : f[0];
        if (array && all_digits(f[2]))
            j.task = uint32_t(std::stoul(f[2]));
        else if (array)
            j.pending = parse_task_ranges(f[2]);
        j.state = f[3];
        if (all_digits(f[4])) {
            const unsigned long raw = std::stoul(f[4]);  // a wait status: exit code << 8 | signal
            j.exit_code = int((raw >> 8) & 0xff);
            j.signal = int(raw & 0x7f);
        }
        j.reason = f[5];
        out.push_back(std::move(j));
    }
    return out;
}

std::vector<JobStatus> query_jobs(const SlurmSettings& settings, const std::vector<std::string>& job_ids) {
    if (job_ids.empty()) return {};
    std::string ids;
    for (const std::string& id : job_ids) ids += (ids.empty() ? "" : ",") + id;
    const std::vector<std::string> argv = {find_client(settings.squeue), "--noheader", "--states=all", "--jobs=" + ids,
                                           "--Format=JobID:|,ArrayJobID:|,ArrayTaskID:|,State:|,exit_code:|,Reason:|"};
    const ProcessResult r = run_process(argv);
    if (!r.ok()) {
        // Every id forgotten (older than MinJobAge): squeue says so and fails.
        if (r.err.find("Invalid job id") != std::string::npos) return {};
        throw Error(ExitCode::Tool, fmt::format("squeue: cannot read the states of jobs {}: {} (fix: check that the "
                                                "Slurm controller is reachable: sinfo)", ids, client_output(r)));
    }
    return parse_squeue(r.out);
}

}  // namespace shatter
