// sward-eval: evaluations of a sward dataset against its ground truth. The first argument picks the command; each
// command parses its own options (commands.h). Without a command word it is the stereo evaluation, as it always was.
#include "tools/sward-eval/commands.h"

#include <cstdio>
#include <string_view>

namespace {

// `sward-eval --help`: the commands first (each has its own --help), then the default command's options.
int overviewHelp(int argc, char** argv) {
    std::fputs("sward-eval: evaluations of a sward dataset against its ground truth\n"
               "Usage: sward-eval [COMMAND] dataset [OPTIONS]\n\n"
               "Commands:\n"
               "  stereo    (the default) stereo matching error against the ground-truth disparity\n"
               "  flow      optical-flow error against the ground-truth forward flow\n"
               "  odometry  stereo visual odometry against the ground-truth poses\n"
               "  look      realism statistics of the previews per region, optionally against real photographs\n\n"
               "`sward-eval COMMAND --help` lists a command's options. The default command's follow.\n\n",
               stdout);
    return stereoMain(argc, argv);
}

} // namespace

int main(int argc, char** argv) {
    const std::string_view command = argc > 1 ? argv[1] : "";
    // The command word becomes argv[0] of the command (its app names itself for the usage line).
    if (command == "stereo") return stereoMain(argc - 1, argv + 1);
    if (command == "flow") return flowMain(argc - 1, argv + 1);
    if (command == "odometry") return odometryMain(argc - 1, argv + 1);
    if (command == "look") return lookMain(argc - 1, argv + 1);
    if (command == "--help" || command == "-h") return overviewHelp(argc, argv);
    return stereoMain(argc, argv);
}
