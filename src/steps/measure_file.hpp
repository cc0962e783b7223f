#pragma once
// The text file a measure writes. It is opened (truncated) at the measure's first firing, not at
// load, so a load that fails later leaves an old file alone; every firing is flushed, so the file is
// complete whenever the host looks at it.
#include <cstdio>
#include <memory>
#include <string>

namespace structmd {

class MeasureFile {
public:
    // owner names the step in messages ("simulationStep.msd"); header is written as the first line
    // (none when empty).
    MeasureFile(std::string owner, std::string path, std::string header);

    // The open stream; opens the file and writes the header on the first call. Throws ERR_IO.
    std::FILE* stream();
    // Throws ERR_IO when what was written cannot reach the file.
    void flush();

private:
    std::string owner_;
    std::string path_;
    std::string header_;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
};

}  // namespace structmd
