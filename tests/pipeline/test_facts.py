from escapement.pipeline.facts import Fact, mask_measured


def test_measured_values_are_marked_and_masked():
    text = f"ratio {Fact('581', measured=True).render()} and error {Fact('1e-16').render()}"
    assert text == "ratio <!--m-->581<!--/m--> and error 1e-16"
    assert mask_measured(text) == mask_measured("ratio <!--m-->612<!--/m--> and error 1e-16")
    assert mask_measured(text) != mask_measured("ratio <!--m-->581<!--/m--> and error 2e-16")
