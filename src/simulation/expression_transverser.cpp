#include "simulation/expression_transverser.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "expression/parser.hpp"
#include "forcefield/expression_compiled.hpp"
#include "transverser/expression_sum.hpp"

namespace structmd {

const std::vector<std::string>& expression_transverser_inputs() {
    static const std::vector<std::string> names = {"r",        "dx",       "dy",       "dz",     "type_i", "type_j",
                                                   "charge_i", "charge_j", "radius_i", "radius_j", "mass_i", "mass_j"};
    return names;
}

std::string ExpressionTransverserSpec::key() const {
    std::ostringstream key;
    key.precision(17);
    key << cutoff << '|' << group << '|' << text;
    return key.str();
}

ExpressionSumKernels expression_sum_kernels(const ExpressionTransverserSpec& spec, const std::string& real) {
    // No data columns: the compiled Function's Params are one unused real (OpaqueSumFunction's layout).
    const RuntimeSource function = compiled_expression_source(spec.graph, {spec.root}, kSumInputs, 0, "int");
    const std::string sum = "structmd::ExpressionSum<RuntimeExpression, " + real + ">";
    ExpressionSumKernels kernels;
    kernels.source =
        "#include \"backends/cuda/launch_kernels.cuh\"\n#include \"transverser/neighbour_traversal.hpp\"\n"
        "#include \"transverser/all_pairs_traversal.hpp\"\n#include \"transverser/expression_sum.hpp\"\n"
        "using namespace structmd;\n" + function.definition;
    kernels.names = {"&structmd::for_each_lanes_kernel<structmd::NeighbourTraversal<" + sum + ", " + real + ">>",
                     "&structmd::for_each_lanes_kernel<structmd::AllPairsTraversal<" + sum + ", " + real + ">>",
                     "&structmd::all_pairs_tiles_kernel<" + sum + ", " + real + ">"};
    return kernels;
}

ExpressionTransverserSpec make_expression_transverser(const std::string& text, const std::string& path,
                                                      double cutoff, int group) {
    if (!std::isfinite(cutoff) || cutoff < 0)
        throw Error(STRUCTMD_ERR_INPUT, path + ": the cutoff must be a finite number >= 0 (0: all pairs)");
    ExpressionTransverserSpec spec;
    spec.text = text;
    spec.path = path;
    spec.cutoff = cutoff;
    spec.group = group;
    const std::vector<std::string>& inputs = expression_transverser_inputs();
    const auto resolve = [&](const std::string& name) -> expression::Binding {
        const auto input = std::find(inputs.begin(), inputs.end(), name);
        if (input == inputs.end()) return {};
        return {expression::Binding::Kind::input, static_cast<int>(input - inputs.begin()), 0};
    };
    try {
        spec.root = expression::parse(text, resolve, spec.graph);
        spec.program = expression::compile(spec.graph, {spec.root});
    } catch (const expression::ExpressionError& e) {
        std::string what = e.what();
        if (what.find("unknown variable") != std::string::npos) {
            std::string known;
            for (const std::string& name : inputs) known += (known.empty() ? "" : ", ") + name;
            what += " (not " + known + ")";
        }
        throw Error(STRUCTMD_ERR_INPUT, path + ": " + what);
    }
    return spec;
}

}  // namespace structmd
