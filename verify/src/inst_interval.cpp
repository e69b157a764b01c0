// Explicit instantiation of the generic pipeline for one scalar type.
#include <qverify/verify/instantiate.hpp>
QVERIFY_INSTANTIATE(::qverify::Interval)
