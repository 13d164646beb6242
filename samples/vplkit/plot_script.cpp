// Runs scripts/plot.py (plot_script.hpp) as a child process: posix_spawnp with an argument
// vector, so folder names need no shell quoting.

#include "plot_script.hpp"

#include "vplkit/error.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#ifndef VPLKIT_PLOT_SCRIPT
#error "VPLKIT_PLOT_SCRIPT (the repository's scripts/plot.py) must be defined by the build"
#endif

extern char** environ;

namespace vplkit::cli {

namespace {

// Runs `argv` (argv[0] looked up on the PATH) and waits for it: its exit status, 128 + the
// signal that ended it, or -1 when it could not be started. `quiet` sends its output to /dev/null.
int run_program(const std::vector<std::string>& argv, bool quiet) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (quiet) {
        posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_adddup2(&actions, 1, 2);
    }
    // The child's lines come after ours.
    std::fflush(stdout);
    std::fflush(stderr);
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) return -1;
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) return -1;
    }
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
}

// The interpreters tried: $VPLKIT_PYTHON alone when set; else the PATH's python3 (which may be a
// pyenv or virtualenv one without matplotlib), then Debian's own, where python3-matplotlib goes.
std::vector<std::string> python_candidates() {
    if (const char* chosen = std::getenv("VPLKIT_PYTHON"); chosen && *chosen) return {chosen};
    return {"python3", "/usr/bin/python3"};
}

// The first candidate that imports matplotlib, or "" when none does; looked up once per run.
const std::string& python_with_matplotlib() {
    static const std::string found = [] {
        for (const std::string& python : python_candidates()) {
            if (run_program({python, "-c", "import matplotlib"}, true) == 0) return python;
        }
        return std::string();
    }();
    return found;
}

std::string joined(const std::vector<std::string>& words) {
    std::string out;
    for (const std::string& w : words) out += (out.empty() ? "" : " ") + w;
    return out;
}

}  // namespace

void draw_plots(const std::string& kind, const std::filesystem::path& folder, const std::vector<std::string>& extra) {
    const std::string script = VPLKIT_PLOT_SCRIPT;
    const std::string& python = python_with_matplotlib();
    if (python.empty()) {
        std::printf(
            "plots skipped: python3-matplotlib is missing (no matplotlib in %s); the CSV/JSON in %s are written\n",
            joined(python_candidates()).c_str(), folder.string().c_str());
        return;
    }
    if (!std::filesystem::exists(script)) {
        std::printf("plots skipped: %s (the plotting script) is missing; the CSV/JSON in %s are written\n",
                    script.c_str(), folder.string().c_str());
        return;
    }
    std::vector<std::string> argv = {python, script, kind, folder.string()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    const int code = run_program(argv, false);
    if (code == 0) return;
    throw Error("plots: `" + joined(argv) + "` " +
                (code < 0 ? std::string("could not be started") : "failed (exit " + std::to_string(code) + ")") +
                "; the CSV/JSON in " + folder.string() + " are written");
}

}  // namespace vplkit::cli
