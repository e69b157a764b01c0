#pragma once
/// \file core.hpp
/// qverify core: projective geometry of quadric shadows and mirror images,
/// generic over the scalar type, header-only, Eigen only. The batch API (many
/// items at once: threads and SIMD packs) is batch/batch.hpp, included on its own.
#include <qverify/core/scalar.hpp>
#include <qverify/core/quadric.hpp>
#include <qverify/core/projective.hpp>
#include <qverify/core/method.hpp>
#include <qverify/core/shadow.hpp>
#include <qverify/core/mirror.hpp>
