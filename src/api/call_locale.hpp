#pragma once
// Numbers are read and written the same whatever locale the host set (a German, French or Spanish
// host calls setlocale(LC_ALL, "de_DE.UTF-8") and the like, making strtod and printf use decimal
// commas): each exported call runs in the "C" locale on its own thread only (uselocale: the host's
// other threads and its global locale stay as they are), and a callback into the host runs in the
// host's locale again.
#include <locale.h>

namespace structmd::api {

class ClassicLocaleScope {
public:
    ClassicLocaleScope() noexcept : host_(uselocale(classic())), outerHost_(host_locale()) { host_locale() = host_; }
    ~ClassicLocaleScope() {
        host_locale() = outerHost_;
        uselocale(host_);
    }
    ClassicLocaleScope(const ClassicLocaleScope&) = delete;
    ClassicLocaleScope& operator=(const ClassicLocaleScope&) = delete;

    // The thread's locale as the host had it when the innermost call began.
    static locale_t& host_locale() noexcept {
        thread_local locale_t host = LC_GLOBAL_LOCALE;
        return host;
    }

private:
    // Made once and never changed; null only when out of memory, and uselocale(null) changes nothing.
    static locale_t classic() noexcept {
        static const locale_t c = newlocale(LC_ALL_MASK, "C", locale_t(0));
        return c;
    }

    locale_t host_, outerHost_;
};

// Around a call into the host's code from inside a call.
class HostLocaleScope {
public:
    HostLocaleScope() noexcept : inside_(uselocale(ClassicLocaleScope::host_locale())) {}
    ~HostLocaleScope() { uselocale(inside_); }
    HostLocaleScope(const HostLocaleScope&) = delete;
    HostLocaleScope& operator=(const HostLocaleScope&) = delete;

private:
    locale_t inside_;
};

}  // namespace structmd::api
