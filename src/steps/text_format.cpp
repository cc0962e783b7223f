#include "steps/text_format.hpp"

#include <cmath>

#include "core/quaternion.hpp"
#include "steps/chemical_elements.hpp"

namespace structmd {

Vec3<double> WrittenParticle::moment_direction() const {
    const Vec3<double> mu = moment();
    const double norm = std::sqrt(dot(mu, mu));
    return norm > 0.0 ? (1.0 / norm) * mu : Vec3<double>{0.0, 0.0, 0.0};
}

Vec3<double> WrittenParticle::body_axis(int axis) const {
    const double* q = quaternion();
    const Real4<double> orientation{q[0], q[1], q[2], q[3]};
    return axis == 0 ? body_x(orientation) : axis == 1 ? body_y(orientation) : body_z(orientation);
}

const char* LinePrinter::separator() {
    const char* before = first_ ? "" : " ";
    first_ = false;
    return before;
}

void LinePrinter::integer(int64_t value) { std::fprintf(file_, "%s%lld", separator(), static_cast<long long>(value)); }
void LinePrinter::real(double value) { std::fprintf(file_, "%s%.8g", separator(), value); }
void LinePrinter::reals(const Vec3<double>& values) {
    real(values.x);
    real(values.y);
    real(values.z);
}
void LinePrinter::text(const std::string& value) { std::fprintf(file_, "%s%s", separator(), value.c_str()); }
void LinePrinter::end() {
    std::fputc('\n', file_);
    first_ = true;
}

void TextFormatWriter::write_frame(std::FILE* f, const TrajectoryFrame& frame) {
    if (atomicNumbers_.size() != frame.typeNames.size()) {
        atomicNumbers_.clear();
        for (const std::string& name : frame.typeNames) atomicNumbers_.push_back(atomic_number(name));
    }
    if (frames() == 0 && !options().append) std::fputs(format_.fileHeader.c_str(), f);
    if (format_.startFrame) format_.startFrame(f, frame);
    LinePrinter printer(f);
    for (size_t k = 0; k < frame.ids.size(); ++k) {
        const WrittenParticle particle(frame, atomicNumbers_, k);
        for (const TextLine& line : format_.lines) {
            for (const Column& column : line) column(particle, printer);
            printer.end();
        }
    }
}

}  // namespace structmd
