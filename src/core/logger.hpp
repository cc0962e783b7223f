#pragma once
// Per-handle log: a library embedded in someone else's program stays quiet unless asked.
#include <cstdio>
#include <string>

namespace structmd {

enum class LogLevel { quiet = 0, warning = 1, info = 2, debug = 3 };

class Logger {
public:
    Logger() = default;
    Logger(LogLevel level, std::FILE* sink) : level_(level), sink_(sink) {}

    bool enabled(LogLevel level) const { return level != LogLevel::quiet && level <= level_ && sink_; }
    void write(LogLevel level, const std::string& message) const {
        if (!enabled(level)) return;
        static const char* const names[] = {"", "warning", "info", "debug"};
        std::fprintf(sink_, "structmd %s: %s\n", names[static_cast<int>(level)], message.c_str());
        std::fflush(sink_);
    }
    void warning(const std::string& m) const { write(LogLevel::warning, m); }
    void info(const std::string& m) const { write(LogLevel::info, m); }

private:
    LogLevel level_ = LogLevel::warning;
    std::FILE* sink_ = stderr;
};

}  // namespace structmd
