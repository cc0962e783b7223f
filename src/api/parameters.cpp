// Run-time parameters: structmd_get_parameter and structmd_set_parameter, with paths in the input's
// own terms. The first call parses the loaded input once and keeps it, without the particle tables
// the engine already holds; a change writes the value into it and reads the force field and the
// integrators again from it, with the checks of a load, and the engine makes both again, keeping
// the particles and the integrators' state. The reader stays the one judge of what a value may be; a
// value it refuses is taken back, leaving the document as it was.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "api/handle.hpp"
#include "core/precise.hpp"
#include "engines/make_engine.hpp"
#include "simulation/read_simulation.hpp"

using namespace structmd;
using namespace structmd::api;

namespace {

using Json = nlohmann::json;

const char* const kForms =
    "run-time parameters are global.ensemble.temperature, integrator.<name>.parameters.<key> and "
    "topology.forceField.<name>.parameters.<key>";

Error refused(const std::string& path, const std::string& why) {
    return Error(STRUCTMD_ERR_ARGUMENT, "parameter " + path + ": " + why);
}

// The ensemble's temperature cell: global.ensemble is a table of one row.
Json* ensemble_temperature(Json& doc, const std::string& path) {
    if (!doc.contains("global") || !doc["global"].contains("ensemble"))
        throw refused(path, "the input has no global.ensemble entry");
    Json& ensemble = doc["global"]["ensemble"];
    if (!ensemble.contains("labels") || !ensemble.contains("data") || ensemble["data"].empty())
        throw refused(path, "global.ensemble has no table");
    const Json& labels = ensemble["labels"];
    for (size_t k = 0; k < labels.size(); ++k)
        if (labels[k] == "temperature") return &ensemble["data"][0][k];
    throw refused(path, "global.ensemble has no temperature column");
}

// The `parameters.<key>` value of entry <name> of a section ("integrator" or "topology.forceField").
// create: a key the entry does not give is added (as null), for the reader to accept or refuse.
Json* entry_parameter(Json& section, const std::string& sectionPath, const std::string& path,
                      const std::string& rest, bool create) {
    const std::string marker = ".parameters.";
    const size_t at = rest.rfind(marker);
    if (at == std::string::npos || at == 0 || at + marker.size() == rest.size())
        throw refused(path, std::string("expected ") + sectionPath + ".<name>.parameters.<key> (" + kForms + ")");
    const std::string name = rest.substr(0, at);
    const std::string key = rest.substr(at + marker.size());
    if (!section.is_object() || !section.contains(name) || !section[name].is_object())
        throw refused(path, "no entry named '" + name + "' in " + sectionPath);
    Json& entry = section[name];
    if (entry.contains("type") && entry["type"].is_array() && !entry["type"].empty() && entry["type"][0] == "Schedule")
        throw refused(path, "the schedule cannot change at run time");
    if (!entry.contains("parameters") || !entry["parameters"].contains(key)) {
        if (!create)
            throw refused(path, "the input does not give it (the component's default applies, if it has one); "
                                "structmd_set_parameter can set it");
        return &entry["parameters"][key];
    }
    return &entry["parameters"][key];
}

// The value `path` names in the document, or ERR_ARGUMENT naming the path when it names nothing that
// can change at run time.
Json* locate(Json& doc, const std::string& path, bool create) {
    const std::string integrator = "integrator.", forceField = "topology.forceField.";
    Json* value = nullptr;
    if (path == "global.ensemble.temperature") {
        value = ensemble_temperature(doc, path);
    } else if (path == "global.ensemble.box") {
        throw refused(path, "the box changes with structmd_set_box");
    } else if (path.rfind(integrator, 0) == 0) {
        if (!doc.contains("integrator")) throw refused(path, "the input has no integrator section");
        value = entry_parameter(doc["integrator"], "integrator", path, path.substr(integrator.size()), create);
    } else if (path.rfind(forceField, 0) == 0) {
        if (!doc.contains("topology") || !doc["topology"].contains("forceField"))
            throw refused(path, "the input has no topology.forceField section");
        value = entry_parameter(doc["topology"]["forceField"], "topology.forceField", path,
                                path.substr(forceField.size()), create);
    } else {
        throw refused(path, std::string("not a run-time parameter (") + kForms + ")");
    }
    if (!value->is_null() && !value->is_number())
        throw refused(path, "the input gives " + value->dump() + ", not a number: it cannot change at run time");
    return value;
}

// The parsed input parameters live in: made at the first call, from the loaded text, which is then
// no longer needed.
input::ParsedDocument& runtime_document(structmd_sim& s) {
    if (!s.runtimeDocument) {
        s.runtimeDocument = read_parameter_document(s.document);
        std::string().swap(s.document);
    }
    return *s.runtimeDocument;
}

// The member `key` of an object, or null.
Json* member(Json* object, const std::string& key) {
    if (!object || !object->is_object()) return nullptr;
    const auto found = object->find(key);
    return found == object->end() ? nullptr : &*found;
}

// What a refused change restores: the entry's parameters object as it was (none: it had none), or
// the temperature cell and the description's temperature.
class Undo {
public:
    // Taken before the change; it modifies nothing, so a path that names nothing is left to locate().
    Undo(Json& doc, const std::string& path, input::SystemDescription& system) : system_(system) {
        const std::string integrator = "integrator.", forceField = "topology.forceField.";
        if (path == "global.ensemble.temperature") {
            cell_ = ensemble_temperature(doc, path);
            savedCell_ = *cell_;
            savedTemperature_ = system.temperature;
            return;
        }
        const bool inIntegrator = path.rfind(integrator, 0) == 0;
        if (!inIntegrator && path.rfind(forceField, 0) != 0) return;
        const std::string rest = path.substr(inIntegrator ? integrator.size() : forceField.size());
        Json* section = inIntegrator ? member(&doc, "integrator") : member(member(&doc, "topology"), "forceField");
        entry_ = member(section, rest.substr(0, rest.rfind(".parameters.")));
        if (Json* parameters = member(entry_, "parameters")) savedParameters_ = *parameters;
    }
    void restore() {
        if (cell_) {
            *cell_ = savedCell_;
            system_.temperature = savedTemperature_;
        } else if (entry_ && savedParameters_) {
            (*entry_)["parameters"] = *savedParameters_;
        } else if (entry_) {
            entry_->erase("parameters");
        }
    }

private:
    input::SystemDescription& system_;
    Json* cell_ = nullptr;
    Json savedCell_;
    double savedTemperature_ = 0.0;
    Json* entry_ = nullptr;
    std::optional<Json> savedParameters_;
};

}  // namespace

extern "C" {

structmd_status structmd_get_parameter(structmd_sim* sim, const char* path, double* value) {
    return with_handle(sim, [&](structmd_sim& s) {
        loaded(s);
        require_pointer(path, "path");
        require_pointer(value, "value");
        *value = locate(runtime_document(s).tracking->document, path, false)->get<double>();
    });
}

structmd_status structmd_set_parameter(structmd_sim* sim, const char* path, double value) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(path, "path");
        if (!std::isfinite(value)) throw refused(path, "value: not a finite number");
        input::ParsedDocument& parsed = runtime_document(s);
        Json& doc = parsed.tracking->document;
        Undo undo(doc, path, parsed.system);
        Json* node = locate(doc, path, true);
        // Whole numbers are written as integers, so integer parameters (a step, a multiplicity) read back.
        if (value == std::nearbyint(value) && std::fabs(value) < 9007199254740992.0)
            *node = static_cast<int64_t>(value);
        else
            *node = value;
        try {
            if (std::string(path) == "global.ensemble.temperature") parsed.system.temperature = value;
            // The present box (structmd_set_box may have changed it): cutoffs are checked against it.
            parsed.system.box = simulation.box();
            RuntimeSpec spec;
            try {
                spec = read_runtime_spec(parsed.system, Logger(LogLevel::quiet, nullptr), s.components->reader());
            } catch (const Error& e) {
                if (e.status() != STRUCTMD_ERR_INPUT) throw;
                throw refused(path, precise(value) + " refused by the input's rules: " + e.what());
            }
            try {
                simulation.change_parameters(spec, *s.components);
            } catch (const Error& e) {
                if (e.status() != STRUCTMD_ERR_ARGUMENT) throw;
                throw refused(path, precise(value) + ": " + e.what());
            }
        } catch (...) {
            undo.restore();
            throw;
        }
    });
}

}  // extern "C"
