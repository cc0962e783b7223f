#pragma once
// The types every backend names for the engine: its buffer, its staging area for host transfers,
// its 3D FFT and its dense Cholesky factorisation. A backend derives from BackendTypes with its own
// templates; the engine reads them as B::Buffer<T> and so on.

namespace structmd {

template <template <class> class BufferT, template <class> class StagingT, template <class> class Fft3dT,
          template <class> class CholeskyT>
struct BackendTypes {
    template <class T>
    using Buffer = BufferT<T>;
    template <class T>
    using Staging = StagingT<T>;
    template <class R>
    using Fft3d = Fft3dT<R>;
    template <class R>
    using Cholesky = CholeskyT<R>;
};

}  // namespace structmd
