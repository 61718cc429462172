// The standard X3D node types MillSim provides.
#include "millsim/core/NodeRegistry.h"
#include "millsim/std/Appearance.h"
#include "millsim/std/Background.h"
#include "millsim/std/BooleanFilter.h"
#include "millsim/std/BooleanToggle.h"
#include "millsim/std/Box.h"
#include "millsim/std/ClipPlane.h"
#include "millsim/std/Collision.h"
#include "millsim/std/ColorInterpolator.h"
#include "millsim/std/ColorNode.h"
#include "millsim/std/Cone.h"
#include "millsim/std/Coordinate.h"
#include "millsim/std/Cylinder.h"
#include "millsim/std/DirectionalLight.h"
#include "millsim/std/FontStyle.h"
#include "millsim/std/Group.h"
#include "millsim/std/ImageTexture.h"
#include "millsim/std/ImportLibrary.h"
#include "millsim/std/IndexedFaceSet.h"
#include "millsim/std/IndexedTriangleSet.h"
#include "millsim/std/Inline.h"
#include "millsim/std/IntegerTrigger.h"
#include "millsim/std/KeySensor.h"
#include "millsim/std/Material.h"
#include "millsim/std/MatrixTransform.h"
#include "millsim/std/MetadataBoolean.h"
#include "millsim/std/MetadataDouble.h"
#include "millsim/std/MetadataFloat.h"
#include "millsim/std/MetadataInteger.h"
#include "millsim/std/MetadataSet.h"
#include "millsim/std/MetadataString.h"
#include "millsim/std/NavigationInfo.h"
#include "millsim/std/Normal.h"
#include "millsim/std/NumberToText.h"
#include "millsim/std/OrientationInterpolator.h"
#include "millsim/std/PointLight.h"
#include "millsim/std/PositionInterpolator.h"
#include "millsim/std/ScalarInterpolator.h"
#include "millsim/std/Shape.h"
#include "millsim/std/Sphere.h"
#include "millsim/std/SpotLight.h"
#include "millsim/std/Switch.h"
#include "millsim/std/Text.h"
#include "millsim/std/TextureCoordinate.h"
#include "millsim/std/TimeSensor.h"
#include "millsim/std/Transform.h"
#include "millsim/std/Viewpoint.h"
#include "millsim/std/WorldInfo.h"

namespace millsim {

void registerStandardNodes(NodeRegistry& r) {
  for (const NodeType* t : {&Appearance::type(), &Background::type(), &Box::type(), &ClipPlane::type(), &Cylinder::type(),
                            &Group::type(), &ImportLibrary::type(), &Inline::type(), &Material::type(),
                            &NavigationInfo::type(), &Shape::type(), &Sphere::type(), &Transform::type(),
                            &Viewpoint::type(), &WorldInfo::type(),
                            // The event nodes and Switch (driven by EventClock, drawn through SceneWalk).
                            &BooleanFilter::type(), &BooleanToggle::type(), &IntegerTrigger::type(), &KeySensor::type(),
                            &OrientationInterpolator::type(), &PositionInterpolator::type(),
                            &ScalarInterpolator::type(), &Switch::type(), &TimeSensor::type(),
                            // Drawn geometry, its vertex data, text, textures and lights (SceneView reads them).
                            &Cone::type(), &ColorNode::type(), &Coordinate::type(), &DirectionalLight::type(),
                            &FontStyle::type(), &ImageTexture::type(), &IndexedFaceSet::type(), &IndexedTriangleSet::type(),
                            &Normal::type(), &PointLight::type(), &SpotLight::type(), &Text::type(), &TextureCoordinate::type(),
                            // MillSim's own: a number shown as text.
                            &NumberToText::type(),
                            &ColorInterpolator::type(), &Collision::type(),
                            // Metadata: what any node's metadata field (and a MetadataSet) holds.
                            &MetadataBoolean::type(), &MetadataDouble::type(), &MetadataFloat::type(),
                            &MetadataInteger::type(), &MetadataSet::type(), &MetadataString::type(),
                            // H3DAPI's, not X3D standard.
                            &MatrixTransform::type()})
    r.add(*t);
}

}  // namespace millsim
