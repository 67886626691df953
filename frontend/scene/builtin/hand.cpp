// hand: ~15k triangles, static, defocus only. Fingers recede from the camera
// and the focus sits on the middle finger, so the wrist is in front of the
// focus plane and the fingertips behind it.
#include "scene/builtin/framing.hpp"
#include "scene/builtin/mesh_builder.hpp"
#include "scene/builtin/scenes.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace blurcull::frontend::builtin {

namespace {

struct Finger {
    glm::vec3 base;
    glm::vec3 direction;
    float lengths[3];
    float radius;
    float curl;
};

// Hand space: fingers along +y, palm facing +z, thumb towards -x.
const Finger kFingers[5] = {
    {{-0.33f, 0.50f, 0.0f}, {-0.08f, 1.0f, 0.0f}, {0.42f, 0.26f, 0.20f}, 0.085f, 0.20f},
    {{-0.11f, 0.54f, 0.0f}, {0.00f, 1.0f, 0.0f}, {0.46f, 0.29f, 0.22f}, 0.090f, 0.16f},
    {{0.11f, 0.51f, 0.0f}, {0.06f, 1.0f, 0.0f}, {0.43f, 0.27f, 0.21f}, 0.085f, 0.22f},
    {{0.32f, 0.44f, 0.0f}, {0.14f, 1.0f, 0.0f}, {0.34f, 0.21f, 0.18f}, 0.072f, 0.28f},
    {{-0.46f, -0.12f, 0.06f}, {-0.75f, 0.62f, 0.30f}, {0.36f, 0.28f, 0.22f}, 0.100f, 0.18f},
};

// Three capsule phalanges per finger, a nail on the last; the thumb (finger
// 4) also gets its metacarpal. Returns the middle of the middle finger's
// first phalanx, where the focus goes.
glm::vec3 add_fingers(MeshBuilder& mesh, const Frame& hand, std::uint32_t skin, std::uint32_t nail) {
    glm::vec3 middle_finger_focus{0.0f};
    for (int f = 0; f < 5; ++f) {
        const Finger& finger = kFingers[f];
        glm::vec3 start = finger.base;
        glm::vec3 direction = glm::normalize(finger.direction);
        float radius = finger.radius;
        if (f == 4) {
            // The thumb's metacarpal runs inside the palm to its base.
            mesh.capsule(hand.point({-0.25f, -0.35f, 0.0f}), hand.point(start), 0.13f, 22, 5, skin);
        }
        for (int joint = 0; joint < 3; ++joint) {
            const glm::vec3 curl_axis = glm::normalize(glm::cross(direction, glm::vec3(0, 0, 1)));
            direction = rotation(curl_axis, finger.curl * static_cast<float>(joint + 1) * 0.6f) * direction;
            const glm::vec3 end = start + direction * finger.lengths[joint];
            mesh.capsule(hand.point(start), hand.point(end), radius, 22, 5, skin);
            if (f == 1 && joint == 0) middle_finger_focus = hand.point(0.5f * (start + end));
            if (joint == 2) {
                const glm::vec3 back = glm::normalize(glm::cross(direction, curl_axis));
                const glm::vec3 center = end - direction * (finger.lengths[joint] * 0.35f) + back * (radius * 0.78f);
                const Frame nail_frame{hand.point(center), hand.axes * glm::mat3(-curl_axis, direction, back)};
                mesh.ellipsoid(nail_frame, {radius * 0.7f, finger.lengths[joint] * 0.32f, radius * 0.25f}, 16, 8,
                               nail);
            }
            start = end;
            radius *= 0.92f;
        }
    }
    return middle_finger_focus;
}

}  // namespace

Scene make_hand(float blur, float aspect) {
    Scene scene;
    scene.name = "hand";
    MeshBuilder mesh(scene);
    const std::uint32_t skin = mesh.material({0.87f, 0.64f, 0.52f}, "skin");
    const std::uint32_t nail = mesh.material({0.96f, 0.84f, 0.80f}, "nail");
    const std::uint32_t sleeve = mesh.material({0.20f, 0.32f, 0.58f}, "sleeve");
    const std::uint32_t wall = mesh.material({0.55f, 0.58f, 0.52f}, "wall");

    // Tilted so the fingers point up and away from the camera.
    const glm::mat3 tilt = rotation({1.0f, 0.0f, 0.0f}, -0.87f);
    const Frame hand{glm::vec3(0.0f), tilt};
    const std::uint32_t hand_first = mesh.vertex_count();

    mesh.superellipsoid(hand, {0.48f, 0.55f, 0.15f}, 0.6f, 0.5f, 64, 32, skin);
    const glm::vec3 middle_finger_focus = add_fingers(mesh, hand, skin, nail);
    // Framing covers palm and fingers; the forearm may run out of the image.
    const std::uint32_t hand_end = mesh.vertex_count();
    mesh.capsule(hand.point({0.0f, -0.40f, 0.0f}), hand.point({0.0f, -1.8f, 0.0f}), 0.30f, 32, 6, skin);
    mesh.capsule(hand.point({0.0f, -1.35f, 0.0f}), hand.point({0.0f, -2.8f, 0.0f}), 0.38f, 32, 6, sleeve);
    // A wall behind the hand, far from the focus plane: a blurred backdrop.
    mesh.grid({-8.0f, -6.0f, -2.8f}, {16.0f, 0.0f, 0.0f}, {0.0f, 13.0f, 0.0f}, 22, 22, wall);

    // Aim at the middle of palm and fingers; focus on the middle finger.
    const glm::vec3 hand_center = hand.point({-0.05f, 0.45f, 0.0f});
    const glm::vec3 eye = hand_center + glm::vec3(0.35f, 0.55f, 3.3f);
    Camera& camera = scene.camera;
    camera.view_open = glm::lookAt(eye, hand_center, kUp);
    camera.view_close = camera.view_open;
    camera.yfov = framing_yfov(scene, camera.view_open, hand_first, hand_end, aspect, 1.15f);
    camera.znear = 0.05f;
    camera.focus_distance = -(camera.view_open * glm::vec4(middle_finger_focus, 1.0f)).z;
    camera.lens_radius = 0.07f * blur;
    scene.light_direction = glm::normalize(glm::vec3(0.4f, 0.8f, 0.6f));
    scene.background = {0.10f, 0.10f, 0.12f};
    return scene;
}

}  // namespace blurcull::frontend::builtin
