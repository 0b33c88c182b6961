from enum import StrEnum

class ConfigurationWrist(StrEnum):
    FLIP = "flip"
    NO_FLIP = "no_flip"

    def __str__(self) -> str:
        return str(self.value)
