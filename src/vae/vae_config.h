// Sizes and training settings of the trajectory VAE (paper section 3.1, Table 1).
#pragma once

#include <string>
#include <vector>

namespace vaegail::vae {

struct VaeConfig {
  std::string name = "walker";
  int state_dim = 18;   // D: components of one state vector x_t
  int action_dim = 6;   // A: components of one action a_t

  // Table 1.
  int lstm_hidden = 200;                    // per direction, both layers of the BiLSTM encoder
  int latent_dim = 20;                      // z
  std::vector<int> action_hidden{200, 200};  // MLP sizes of the action decoder
  int wavenet_channels = 32;                // C: residual channels of the state decoder
  int wavenet_layers = 6;                   // dilated causal layers

  // Not in the paper. 5 Gaussians per state component: the paper only says "a mixture of
  // Gaussians"; 5 is enough for the multi-modal one-step transitions of contact dynamics
  // (foot on / off the ground) while keeping the head (3K outputs) small next to C = 32.
  int mixture_components = 5;
  // A learned per-component position bias in every gated layer; without it a WaveNet with
  // only global conditioning cannot tell component k from k' (see state_decoder.h).
  bool position_embedding = true;
  // Not in the paper. Empty, or one state index per action component: the action decoder then
  // models a_j - x_t[k_j] instead of a_j. For position servos (the arm: an action is a set of
  // joint-angle commands, x_t starts with the joint angles) the command is the current angle
  // plus a small step; an MLP asked for the absolute command must carry the angle through its
  // tanh layers, and its small errors, fed back through the servos, make a rollout drift away
  // from every demonstration whatever z says.
  std::vector<int> action_relative_to_state;
  // Not in the paper, which does not say. true: the action decoder's std is a function of
  // (x_t, z); false: one learned std per action component. A state-dependent std lets the
  // likelihood give up on steps whose action only z can tell (the arm's first command, the same
  // home state for every target): a large std there makes their error cheap, and the decoder
  // never learns to read z. A shared std weighs every step's error alike.
  bool action_std_depends_on_state = true;
  // Not in the paper. 0, or a floor (raw units) on the state std the action decoder's input is
  // divided by: it then sees (x - mean) / max(std, floor) while the encoder and the state
  // decoder keep (x - mean) / std. A component nearly constant in the demonstrations (the
  // humanoid's hand joints: std 1e-3) is otherwise blown up hundreds of times once a state
  // leaves them a little, a rollout's or a noise-perturbed demonstration's, and saturates the
  // decoder's tanh units (../shared/reference/held_torque_dagger floors its inputs' std at 0.05).
  double policy_state_std_floor = 0.0;
  // Not in the paper, which encodes whole states. Empty, or the state components the encoder
  // reads (the decoders always see the whole state). The arm's grip position says where a
  // reach ends; its joint angles and velocities also carry each expert's idiosyncratic path,
  // which tells 50 training experts apart without saying anything about an unseen one. Likewise
  // the walker's root (height, pitch, root velocities) says how fast it goes, while its joints
  // carry each expert's gait: an encoder reading them places an unseen expert beside the
  // training expert of the nearest gait, whatever that one's speed.
  std::vector<int> encoder_state_indices;

  // Training. The paper gives no VAE optimiser settings; these are Adam's usual ones.
  double learning_rate = 1e-4;
  int batch_size = 32;
  // Weight of KL(q(z|x) || N(0, I)) in the loss; 1 is the paper's objective (the ELBO).
  double kl_weight = 1.0;
  // Adam's L2 penalty on every weight (0: none, the paper's objective).
  double weight_decay = 0.0;
  // Not in the paper. Std of Gaussian noise added to the encoder's input (normalised states)
  // during training only; the decoders see clean states. An encoder that must name a
  // demonstration through noise has to rest on what the whole trajectory shows (where the arm
  // comes to rest) rather than on small idiosyncrasies that tell 50 training experts apart
  // and say nothing about an unseen one.
  double encoder_input_noise = 0.0;
  // Not in the paper. 0: a constant learning rate. E > 0: cosine decay from learning_rate at
  // epoch 1 towards 0 after epoch E, so that a run's last epoch is a settled point rather than
  // one draw of a noisy constant-rate walk (whose embedding and imitation scores jump from
  // epoch to epoch), and "the last epoch", fixed before training, is a fair choice.
  int lr_decay_epochs = 0;

  // The named presets of Table 1. state_dim / action_dim depend on the environment's
  // observation and action spaces; the walker's are this project's 18 and 6.
  static VaeConfig walker(int state_dim = 18, int action_dim = 6);
  static VaeConfig arm(int state_dim, int action_dim);       // "Jaco" in Table 1
  static VaeConfig humanoid(int state_dim, int action_dim);
  // "walker" | "arm" | "jaco" | "humanoid"; throws std::invalid_argument otherwise.
  static VaeConfig preset(const std::string& name, int state_dim, int action_dim);

  // Throws std::invalid_argument naming the first bad field.
  void validate() const;

  std::string to_json() const;
  // Missing keys keep the value of `defaults` (by default the walker preset); unknown keys
  // throw, so a typo in a config file is an error and not a silent default.
  static VaeConfig from_json(const std::string& text, const VaeConfig& defaults);
  static VaeConfig from_json(const std::string& text);
  void save(const std::string& path) const;  // atomically
  static VaeConfig load(const std::string& path, const VaeConfig& defaults);
  static VaeConfig load(const std::string& path);

  bool operator==(const VaeConfig& other) const;
  bool operator!=(const VaeConfig& other) const { return !(*this == other); }
};

}  // namespace vaegail::vae
