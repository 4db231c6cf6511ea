// sward-eval: evaluations of a sward dataset against its ground truth. The first argument picks the command; each
// command parses its own options (commands.h). Without a command word it is the stereo evaluation, as it always was.
#include "tools/sward-eval/commands.h"

#include <string_view>

int main(int argc, char** argv) {
    const std::string_view command = argc > 1 ? argv[1] : "";
    // argv[0] becomes the command word: the command's usage line reads "sward-eval stereo ..."
    if (command == "stereo") return stereoMain(argc - 1, argv + 1);
    if (command == "flow") return flowMain(argc - 1, argv + 1);
    if (command == "odometry") return odometryMain(argc - 1, argv + 1);
    if (command == "look") return lookMain(argc - 1, argv + 1);
    return stereoMain(argc, argv);
}
